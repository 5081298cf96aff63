// Why a file the modeller loads by URL (the solver worker's script, its WASM)
// could not be used, found out after the browser's own failure said nothing
// useful: a module worker's failed load fires an 'error' event with no
// message, and a WASM compile of a 404 page says only "expected magic word".

const WASM_MAGIC = [0x00, 0x61, 0x73, 0x6d];

/**
 * Resolves a short reason ('HTTP 404', 'it could not be fetched: ...', 'it
 * is not WebAssembly (it begins "Not F")'), or null when `url` fetches and,
 * with `wasm`, begins as WebAssembly does.
 */
export async function urlProblem(url, { wasm = false } = {}) {
  let response;
  try {
    response = await fetch(url);
  } catch (error) {
    return `it could not be fetched: ${error.message}`;
  }
  if (!response.ok) return `HTTP ${response.status}`;
  if (!wasm) return null;
  const head = new Uint8Array((await response.arrayBuffer()).slice(0, 4));
  if (WASM_MAGIC.every((byte, i) => head[i] === byte)) return null;
  const text = Array.from(head, (byte) => (byte >= 0x20 && byte < 0x7f ? String.fromCharCode(byte) : '.')).join('');
  return `it is not WebAssembly (it begins "${text}")`;
}
