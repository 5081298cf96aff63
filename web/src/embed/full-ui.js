// The full UI of a modeller (ui: 'full'): the side panel's sections, the
// pattern pane, the status bar, the messages over the viewport, drag-and-drop
// loading onto the modeller, the Frame button, the editing keys and their
// overlay (?), all in its own layout (modeller-layout.js); on narrow screens
// the panel is a bottom sheet. The styles: ui/styles.css,
// ui/narrow-layout.css and ui/focus-and-overlays.css (together the package's
// style.css).
import '../ui/styles.css';
import '../ui/narrow-layout.css';
import '../ui/focus-and-overlays.css';
import { opsPanel } from '../document/ops-panel.js';
import { installAnnouncer } from '../ui/announcer.js';
import { selectRegionAtViewCentre } from '../editor/region-at-view-centre.js';
import { installEditingKeys } from '../interaction/editing-keys.js';
import { directionPanel } from '../ui/direction-panel.js';
import { displayPanel } from '../ui/display-panel.js';
import { installDropZone } from '../ui/drop-zone.js';
import { showWhen } from '../ui/fields.js';
import { filePanel } from '../ui/file-panel.js';
import { flattenPanel } from '../ui/flatten-panel.js';
import { frameButton } from '../ui/frame-button.js';
import { historyButtons } from '../ui/history-panel.js';
import { installMessages } from '../ui/messages.js';
import { methodPanel } from '../ui/method-panel.js';
import { modePanel, modeSwitch } from '../ui/mode-switch.js';
import { panelSheetToggle } from '../ui/panel-sheet.js';
import { patternPane } from '../ui/pattern-pane.js';
import { selectionPanel } from '../ui/selection-panel.js';
import { replaceDialog } from '../ui/replace-dialog.js';
import { shortcutDialog } from '../ui/shortcut-dialog.js';
import { statusBar } from '../ui/status-bar.js';
import { toolPanel } from '../ui/tool-panel.js';
import { claimUniqueIds } from '../ui/unique-ids.js';

export function installFullUi(layout, { api, editor, settings, tools, viewer, picker, reportError, lifetime, keyTarget }) {
  // The editor has reported a refused selection already (the banner).
  // api.select reports a refusal itself (the banner and the 'error' event); the rejection needs no second word.
  const selectRegion = (options) => selectRegionAtViewCentre({ api, editor, viewer, picker, settings }, options)?.catch(() => {});
  const inMode = (mode, element) => showWhen(settings, 'mode', element, (current) => current === mode);
  const files = filePanel({ api, editor, reportError, askToReplace: replaceDialog(layout.root).ask });
  layout.sidePanel.append(
    modeSwitch({ settings, app: layout.root }),
    files.element,
    historyButtons({ api, editor }),
    opsPanel({ api, editor }),
    toolPanel({ editor, settings, tools, reportError, selectRegion }),
    selectionPanel({ api, editor }),
    inMode('deform', modePanel('deform', directionPanel({ settings }), methodPanel({ settings }))),
    inMode('flatten', modePanel('flatten', flattenPanel({ api, editor, settings, reportError }))),
    displayPanel({ settings }),
  );
  panelSheetToggle(layout.sidePanel, lifetime);
  patternPane(layout.patternPane, { editor, settings, lifetime });
  statusBar(layout.statusBar, { editor, viewer, lifetime });
  const announcer = installAnnouncer(layout.statusBar, { editor });
  const messages = installMessages(layout.viewport, { editor, lifetime });
  installDropZone(layout.root, layout.dropOverlay, { api, reportError, lifetime, mayReplace: files.mayReplace });
  frameButton(layout.viewport, { api });
  const dialog = shortcutDialog(layout.root, { tools });
  const toolChosen = (id) => announcer.say(`${tools.get(id).label} tool`);
  installEditingKeys(keyTarget, lifetime, { settings, dialog, selectRegion, files, toolChosen });
  claimUniqueIds(layout.root, lifetime);
  // A value a panel field did not take is said (ui/fields.js), until that field takes one.
  settings.on('refused', ({ message, field }) => editor.emit('notice', { message, source: 'field', field }));
  settings.on('accepted', ({ field }) => messages.clearFieldNotice(field));
}
