// Autosave of the edit document and its base mesh's bytes in IndexedDB, so a
// reload restores the work. One record: {document, meshName, meshBytes,
// savedAt}; meshBytes is a Blob of the file (older records hold an
// ArrayBuffer: editor.load reads both). A failed save (quota, private mode)
// rejects with code 'storage' and a message that says the work in the page
// is kept; it never touches the in-memory document.
const DATABASE = 'anisoform';
const STORE = 'autosave';
const KEY = 'current';

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

// Off until enable(): one database per origin, so only the standalone site
// autosaves; two embedded modellers on one page would overwrite each other.
export class Autosave {
  /** Saves are chained, so the last one written is the last one asked for. */
  #chain = Promise.resolve();
  enabled = false;

  save({ document, meshName, meshBytes }) {
    if (!this.enabled) return Promise.resolve();
    const record = { document, meshName, meshBytes, savedAt: Date.now() };
    // A save waiting in the chain is dropped if autosave ends before its turn
    // (a disposed modeller writes nothing after a new one has started).
    const saving = this.#chain.then(() => this.enabled && transact('readwrite', (store) => store.put(record, KEY)));
    this.#chain = saving.catch(() => {});
    return saving.catch((error) => {
      throw storageError('save', error);
    });
  }

  async load() {
    if (!this.enabled) return null;
    await this.#chain;
    try {
      return (await transact('readonly', (store) => store.get(KEY))) ?? null;
    } catch (error) {
      throw storageError('read the saved work', error);
    }
  }
}
