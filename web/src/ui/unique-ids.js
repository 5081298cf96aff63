// Element ids unique on the page, whatever number of modellers it holds.
// A panel names its controls by fixed ids ('direction-source',
// 'file-input'), which the labels' `for` and the ARIA references use: with
// two modellers of the full UI on a page, every such id was there twice, and
// a label (Open…, Wireframe) worked the first modeller's control from the
// second's panel. The first modeller keeps the plain ids (the standalone
// site's, which its tests and style sheets name); a later one, while an
// earlier one holds them, gets them numbered ('direction-source-2'), with
// its references renamed alike. Released when its modeller is disposed.

// An id's holders: base id -> the numbers in use (1 is the plain id).
const held = new Map();

const REFERENCES = ['for', 'aria-labelledby', 'aria-describedby', 'aria-controls'];

/** Makes the ids under `root` unique among the live modellers; `lifetime` releases them. */
export function claimUniqueIds(root, lifetime) {
  const renamed = new Map();
  const claimed = [];
  for (const element of root.querySelectorAll('[id]')) {
    const base = element.id;
    const numbers = held.get(base) ?? new Set();
    held.set(base, numbers);
    let n = 1;
    while (numbers.has(n)) n += 1;
    numbers.add(n);
    claimed.push([base, n]);
    if (n > 1) renamed.set(base, (element.id = `${base}-${n}`));
  }
  if (renamed.size > 0) {
    const selector = REFERENCES.map((name) => `[${name}]`).join(',');
    for (const element of root.querySelectorAll(selector)) {
      for (const name of REFERENCES) {
        const value = element.getAttribute(name);
        if (value === null) continue;
        element.setAttribute(name, value.split(/\s+/).map((id) => renamed.get(id) ?? id).join(' '));
      }
    }
  }
  lifetime.defer(() => {
    for (const [base, n] of claimed) held.get(base)?.delete(n);
  });
}
