// The `mesh` option of createModeller and the element's `src`: a URL (string
// or URL, resolved against the page) is fetched; a File, Blob, ArrayBuffer or
// typed array is passed on to the editor's load() as is. The name (whose
// extension picks the reader) comes from `name`, the File or the URL's path.
export async function resolveMeshSource(source, name) {
  if (typeof source === 'string' || source instanceof URL) {
    const url = new URL(source, document.baseURI);
    let response;
    try {
      response = await fetch(url);
    } catch (error) {
      throw Object.assign(new Error(`The mesh ${url.pathname} could not be fetched: ${error.message}`), { code: 'bad-file' });
    }
    if (!response.ok) {
      throw Object.assign(new Error(`The mesh ${url.pathname} could not be fetched (HTTP ${response.status})`), { code: 'bad-file' });
    }
    const fromPath = decodeURIComponent(url.pathname.split('/').pop() ?? '');
    return { data: await response.arrayBuffer(), name: name ?? fromPath };
  }
  return { data: source, name: name ?? source?.name };
}
