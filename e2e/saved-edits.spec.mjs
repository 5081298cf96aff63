// Saved edits: the Save edits button offers the edit document as a file, and
// Open… (the picker, or a drop on the view) replays it on the mesh loaded or
// on the mesh file opened with it, to bitwise the positions it was saved
// with. A file that is not an edit document, edits opened on another mesh,
// or two meshes at once are refused, naming the problem, and the work in the
// page stays.
import { readFileSync, writeFileSync } from 'node:fs';
import { basename } from 'node:path';
import { schemaErrors } from '../docs/document-schema.mjs';
import { armChange, evaluateBulk, expect, meshPath, openApp, replaceWorkIfAsked, selectUpperHalf, test, uploadFile } from './support.mjs';

async function recordErrors(page) {
  await page.evaluate(() => {
    window.__errors = [];
    window.anisoform.on('error', (event) => window.__errors.push(event.message));
  });
}

const positions = (page) => evaluateBulk(page, () => Array.from(window.anisoform.positions()));
const opCount = (page) => page.evaluate(() => window.anisoform.document().ops.length);

// Twists the upper half of the mesh loaded with the Twist tool's Apply.
async function twistUpperHalf(page) {
  await selectUpperHalf(page);
  await page.getByTestId('tool-twist').click();
  const committed = await armChange(page, 'positions');
  await page.getByTestId('apply-twist').click();
  await committed();
}

async function openInPicker(page, files) {
  const opened = await armChange(page, 'document');
  await page.getByTestId('file-input').setInputFiles(files);
  await opened();
}

async function dropFiles(page, paths) {
  // As base64 text: as an array of numbers, Spot's 330 kB took seconds to cross.
  const files = paths.map((path) => ({ name: basename(path), base64: readFileSync(path).toString('base64') }));
  const dataTransfer = await page.evaluateHandle((list) => {
    const transfer = new DataTransfer();
    for (const { name, base64 } of list) transfer.items.add(new File([Uint8Array.from(atob(base64), (c) => c.charCodeAt(0))], name));
    return transfer;
  }, files);
  const opened = await armChange(page, 'document');
  await page.dispatchEvent('main.viewport', 'drop', { dataTransfer });
  await replaceWorkIfAsked(page);
  await opened();
}

test('Save edits, then Open… them on the mesh loaded, or drop them with their mesh on another', async ({ page }, testInfo) => {
  const pageErrors = await openApp(page);
  await recordErrors(page);
  const rest = await positions(page);
  await expect(page.getByTestId('save-edits')).toBeDisabled(); // nothing to save yet
  await twistUpperHalf(page);
  const edited = await positions(page);
  expect(edited).not.toEqual(rest);

  const [download] = await Promise.all([page.waitForEvent('download'), page.getByTestId('save-edits').click()]);
  expect(download.suggestedFilename()).toBe('spot_triangulated-edits.json');
  const saved = testInfo.outputPath('spot_triangulated-edits.json');
  await download.saveAs(saved);
  const json = JSON.parse(readFileSync(saved, 'utf8'));
  expect(json.format).toBe('anisoform-document');
  expect(json.mesh.name).toBe('spot_triangulated.obj');
  expect(json.ops.map((entry) => Object.keys(entry.op.transform))).toEqual([['twist']]);
  expect(schemaErrors(json)).toEqual([]);  // the schema embedders are given

  // Reset clears the edits; the saved ones, opened alone, replay on the mesh loaded.
  await page.getByTestId('reset').click();
  await expect.poll(() => opCount(page)).toBe(0);
  expect(await positions(page)).toEqual(rest);
  await expect(page.getByTestId('save-edits')).toBeDisabled();
  await openInPicker(page, saved);
  expect(await opCount(page)).toBe(1);
  expect(await positions(page)).toEqual(edited);

  // On another mesh, the saved edits dropped with their mesh file bring both back.
  expect((await uploadFile(page, meshPath('open/hemisphere.obj'))).ok).toBe(true);
  await dropFiles(page, [saved, meshPath('closed/spot_triangulated.obj')]);
  expect(await page.evaluate(() => window.anisoform.info().vertices)).toBe(rest.length / 3);
  expect(await opCount(page)).toBe(1);
  expect(await positions(page)).toEqual(edited);
  // Dropped with the same mesh under another file name, the edits take that name.
  const renamed = testInfo.outputPath('spot-copy.obj');
  writeFileSync(renamed, readFileSync(meshPath('closed/spot_triangulated.obj')));
  await dropFiles(page, [saved, renamed]);
  expect(await positions(page)).toEqual(edited);
  expect(await page.evaluate(() => window.anisoform.document().mesh.name)).toBe('spot-copy.obj');

  // And they can be undone as edits made here.
  await page.getByTestId('undo').click();
  await expect.poll(() => positions(page)).toEqual(rest);
  expect(await page.evaluate(() => window.__errors)).toEqual([]);
  expect(pageErrors).toEqual([]);
});

test('saved edits on another mesh, a file that is not saved edits, two meshes: refused, the work kept', async ({ page }, testInfo) => {
  const pageErrors = await openApp(page);
  await twistUpperHalf(page);
  const saved = testInfo.outputPath('spot-edits.json');
  writeFileSync(saved, JSON.stringify(await page.evaluate(() => window.anisoform.document())));
  expect((await uploadFile(page, meshPath('open/hemisphere.obj'))).ok).toBe(true);
  await twistUpperHalf(page);
  await recordErrors(page);
  const kept = await positions(page);
  const banner = page.getByTestId('error');

  await page.getByTestId('file-input').setInputFiles(saved);
  await replaceWorkIfAsked(page);
  await expect(banner).toContainText('The document was not opened');
  await expect(banner).toContainText("'spot_triangulated.obj', 2930 vertices");
  await expect(banner).toContainText('does not match the loaded mesh');

  const broken = testInfo.outputPath('broken-edits.json');
  writeFileSync(broken, '{"format": "anisoform-document", "version": 1, "ops": [');
  await page.getByTestId('file-input').setInputFiles(broken);
  await expect(banner).toContainText('broken-edits.json is not saved edits');

  await page.getByTestId('file-input').setInputFiles([meshPath('open/hemisphere.obj'), meshPath('closed/torus.obj')]);
  await expect(banner).toContainText('hemisphere.obj, torus.obj');

  // Opened with another mesh file, the edits are refused naming the mesh they were made on.
  await page.getByTestId('file-input').setInputFiles([saved, meshPath('closed/torus.obj')]);
  await replaceWorkIfAsked(page);
  await expect(banner).toContainText("('spot_triangulated.obj', 2930 vertices, 5856 triangles) does not match the mesh of torus.obj");

  const messages = await page.evaluate(() => window.__errors);
  expect(messages).toHaveLength(4);
  expect(messages[1]).toContain('Nothing was opened');
  expect(await positions(page)).toEqual(kept);
  expect(await opCount(page)).toBe(1);
  expect(pageErrors).toEqual([]);
});

test('opening a mesh or saved edits over edits made asks first: keep working, save them first, or open without saving', async ({ page }, testInfo) => {
  const pageErrors = await openApp(page);
  await twistUpperHalf(page);
  const edited = await positions(page);
  const dialog = page.getByTestId('replace-dialog');
  const pick = () => page.getByTestId('file-input').setInputFiles(meshPath('open/hemisphere.obj'));

  // Keep working (the focused answer), and Esc: nothing is opened, the edit stays.
  await pick();
  await expect(dialog).toBeVisible();
  await expect(dialog).toContainText('Opening hemisphere.obj replaces the 1 edit of spot_triangulated.obj: Undo cannot bring it back.');
  await expect(page.getByTestId('replace-cancel')).toBeFocused();
  await page.keyboard.press('Enter');
  await expect(dialog).toBeHidden();
  await pick();
  await expect(dialog).toBeVisible();
  await page.keyboard.press('Escape');
  await expect(dialog).toBeHidden();
  await page.waitForTimeout(300);
  expect(await page.evaluate(() => window.anisoform.info().vertices)).toBe(2930);
  expect(await opCount(page)).toBe(1);
  expect(await positions(page)).toEqual(edited);

  // Save edits, then open: the edits are downloaded as Save edits gives them, then the mesh opens.
  await pick();
  const [download] = await Promise.all([page.waitForEvent('download'), page.getByTestId('replace-save').click()]);
  expect(download.suggestedFilename()).toBe('spot_triangulated-edits.json');
  const saved = testInfo.outputPath('saved-before-open.json');
  await download.saveAs(saved);
  expect(JSON.parse(readFileSync(saved, 'utf8')).ops).toHaveLength(1);
  await expect.poll(() => page.evaluate(() => window.anisoform.info().vertices)).not.toBe(2930);
  expect(await opCount(page)).toBe(0);

  // With no edits, nothing is asked: the saved edits and their mesh open at once, the edit back.
  await openInPicker(page, [saved, meshPath('closed/spot_triangulated.obj')]);
  await expect(dialog).toBeHidden();
  expect(await positions(page)).toEqual(edited);
  expect(pageErrors).toEqual([]);
});
