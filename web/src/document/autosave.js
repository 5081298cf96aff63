// Autosave of the edit document and its base mesh's bytes in IndexedDB, so a
// reload restores the work. A record: {document, meshName, meshBytes,
// savedAt}; meshBytes is a Blob of the file (older records hold an
// ArrayBuffer: editor.load reads both). A failed save (quota, private mode)
// rejects with code 'storage' and a message that says the work in the page
// is kept; it never touches the in-memory document.
//
// One record per browser tab (its id in sessionStorage, which a reload
// keeps), and 'current' says which tab saved last: a reload restores its own
// tab's work, a new tab the latest. With one record for all, a reload of one
// tab brought back another tab's mesh and edits, and its own were gone.
const DATABASE = 'anisoform';
const STORE = 'autosave';
const LATEST = 'current';
const TAB_KEYS = globalThis.IDBKeyRange?.bound('tab:', 'tab:\uffff');
// The tabs' records kept besides the latest: each holds a mesh file.
const KEEP_TABS = 4;

// This tab's id, kept over reloads; without sessionStorage (a sandboxed
// frame) one per page: its reload then restores the latest work.
//
// A tab duplicated, or opened from the page (window.open), starts with a
// copy of this tab's sessionStorage, so with its id: it restores this tab's
// work (a copy), and once it learns that a live tab holds that id
// (BroadcastChannel) it takes an id of its own before saving. With one id,
// the two overwrote each other's work.
const TAB_ID = 'anisoform-tab';
let tabId = null;
let tabs = null;
const randomId = () => globalThis.crypto?.randomUUID?.() ?? `${Date.now()}-${Math.random()}`;

function tabKey() {
  if (tabId === null) {
    try {
      tabId = sessionStorage.getItem(TAB_ID) ?? randomId();
      sessionStorage.setItem(TAB_ID, tabId);
    } catch {
      tabId = randomId();
    }
    watchForTwins();
  }
  return `tab:${tabId}`;
}

function watchForTwins() {
  if (typeof BroadcastChannel !== 'function') return;
  tabs = new BroadcastChannel('anisoform-autosave-tabs');
  tabs.onmessage = ({ data }) => {
    if (data?.claim === tabId) {
      tabs.postMessage({ taken: tabId }); // a tab started with my id: it must move
    } else if (data?.taken === tabId) {
      tabId = randomId();
      try {
        sessionStorage.setItem(TAB_ID, tabId);
      } catch {
        // the id lives for this page only
      }
    }
  };
  tabs.postMessage({ claim: tabId });
}

function storageError(action, error) {
  const reason = error?.name === 'QuotaExceededError' ? 'the browser storage quota is full' : error?.message ?? String(error);
  return Object.assign(new Error(`Autosave could not ${action}: ${reason}. Your work in this page is kept; export it to be safe.`),
    { code: 'storage', cause: error });
}

function open() {
  return new Promise((resolve, reject) => {
    if (typeof indexedDB === 'undefined') {
      reject(new Error('IndexedDB is not available'));
      return;
    }
    const request = indexedDB.open(DATABASE, 1);
    request.onupgradeneeded = () => request.result.createObjectStore(STORE);
    request.onsuccess = () => resolve(request.result);
    request.onerror = () => reject(request.error);
  });
}

async function transact(mode, work) {
  const database = await open();
  try {
    return await new Promise((resolve, reject) => {
      const transaction = database.transaction(STORE, mode);
      const request = work(transaction.objectStore(STORE));
      transaction.oncomplete = () => resolve(request?.result);
      transaction.onerror = () => reject(transaction.error ?? request?.error);
      transaction.onabort = () => reject(transaction.error ?? new Error('the transaction was aborted'));
    });
  } finally {
    database.close();
  }
}

// Beside each tab's work, under 'view:' and its key, the view of that work
// (view-autosave.js: the selection, the tool and its settings, the camera):
// written far more often than the work, so apart from its mesh file.
const viewKey = (workKey) => `view:${workKey}`;
// sessionStorage's key of the view saved as the page went (saveViewOnLeave).
const LEAVING_VIEW = 'anisoform-leaving-view';

function base64Of(bytes) {
  let text = '';
  for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(text);
}

// The view this tab saved as it went, if it is of the work `workKey`
// (once: it is removed), its selection a Float32Array again; else null.
function takeLeavingView(workKey) {
  try {
    const text = sessionStorage.getItem(LEAVING_VIEW);
    sessionStorage.removeItem(LEAVING_VIEW);
    const view = text && JSON.parse(text);
    if (!view || view.tab !== workKey) return null;
    const selection = typeof view.selection === 'string'
      ? new Float32Array(Uint8Array.from(atob(view.selection), (c) => c.charCodeAt(0)).buffer) : null;
    return { ...view, selection };
  } catch {
    return null;
  }
}

// Off until enable(): one database per origin, so only the standalone site
// autosaves; two embedded modellers on one page would overwrite each other.
export class Autosave {
  /** Saves are chained, so the last one written is the last one asked for. */
  #chain = Promise.resolve();
  /** The key of the work load() found last: its view goes with it (loadView). */
  #loadedKey = null;
  enabled = false;

  save({ document, meshName, meshBytes }) {
    if (!this.enabled) return Promise.resolve();
    const record = { document, meshName, meshBytes, savedAt: Date.now() };
    // A save waiting in the chain is dropped if autosave ends before its turn
    // (a disposed modeller writes nothing after a new one has started).
    const key = tabKey();
    const saving = this.#chain.then(() => this.enabled && transact('readwrite', (store) => {
      store.put(record, key);
      store.put({ tab: key, savedAt: record.savedAt }, LATEST);
      pruneTabs(store, key);
    }));
    this.#chain = saving.catch(() => {});
    return saving.catch((error) => {
      throw storageError('save', error);
    });
  }

  async load() {
    if (!this.enabled) return null;
    await this.#chain;
    this.#loadedKey = null;
    try {
      const own = await transact('readonly', (store) => store.get(tabKey()));
      if (own) return this.#found(tabKey(), own);
      const latest = await transact('readonly', (store) => store.get(LATEST));
      // A record of a build before the tabs' own: the work itself.
      if (!latest?.tab) return latest ?? null;
      return this.#found(latest.tab, await transact('readonly', (store) => store.get(latest.tab)));
    } catch (error) {
      throw storageError('read the saved work', error);
    }
  }

  #found(key, record) {
    this.#loadedKey = record ? key : null;
    return record ?? null;
  }

  /** Saves this tab's view (view-autosave.js), after the saves asked for before. */
  saveView(view, { leaving = false } = {}) {
    if (!this.enabled) return Promise.resolve();
    if (leaving) this.#saveViewOnLeave(view);
    const key = viewKey(tabKey());
    const saving = this.#chain.then(() => this.enabled && transact('readwrite', (store) => {
      store.put(view, key);
    }));
    this.#chain = saving.catch(() => {});
    return saving.catch((error) => {
      throw storageError('save the view', error);
    });
  }

  /**
   * Saves this tab's view at once, as the page goes (pagehide): a database
   * write begun then does not end before the page does (a reload within
   * the view's 250 ms wait lost the last orbit or stroke). Kept in the tab's
   * sessionStorage, which a reload keeps; too large for it (a huge
   * selection), it is not kept there.
   */
  #saveViewOnLeave(view) {
    if (!this.enabled) return;
    try {
      const selection = view.selection && base64Of(new Uint8Array(view.selection.buffer, view.selection.byteOffset, view.selection.byteLength));
      sessionStorage.setItem(LEAVING_VIEW, JSON.stringify({ ...view, selection, tab: tabKey() }));
    } catch {
      try {
        sessionStorage.removeItem(LEAVING_VIEW);
      } catch {
        // No sessionStorage (a sandboxed frame): the database's copy is all.
      }
    }
  }

  /** The view saved beside the work load() found last (its tab's; the later of its two copies), or null. */
  async loadView() {
    if (!this.enabled || !this.#loadedKey) return null;
    const key = viewKey(this.#loadedKey);
    const leaving = takeLeavingView(this.#loadedKey);
    try {
      const stored = (await transact('readonly', (store) => store.get(key))) ?? null;
      return leaving && !(stored?.savedAt > leaving.savedAt) ? leaving : stored;
    } catch (error) {
      throw storageError('read the saved view', error);
    }
  }
}

// Deletes the oldest tabs' records beyond KEEP_TABS (never `own`).
function pruneTabs(store, own) {
  if (!TAB_KEYS) return;
  const keys = store.getAllKeys(TAB_KEYS);
  const records = store.getAll(TAB_KEYS);
  records.onsuccess = () => {
    const byAge = keys.result.map((key, i) => ({ key, savedAt: records.result[i]?.savedAt ?? 0 }))
      .filter(({ key }) => key !== own)
      .sort((a, b) => b.savedAt - a.savedAt);
    byAge.slice(KEEP_TABS - 1).forEach(({ key }) => {
      store.delete(key);
      store.delete(viewKey(key));
    });
  };
}
