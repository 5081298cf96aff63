// The `mesh` and `document` options of createModeller and the element's
// `src` and `edits`: a URL (string or URL, resolved against the page) is
// fetched; anything else is passed on as is (a mesh's File, Blob,
// ArrayBuffer or typed array to the editor's load(); a document's object to
// api.open). A mesh's name (whose extension picks the reader) comes from
// `name`, the File or the URL's path.
const isUrl = (source) => typeof source === 'string' || source instanceof URL;

async function fetched(source, what) {
  const url = new URL(source, document.baseURI);
  let response;
  try {
    response = await fetch(url);
  } catch (error) {
    throw Object.assign(new Error(`${what} ${shownUrl(url)} could not be fetched: ${error.message}`), { code: 'bad-file' });
  }
  if (!response.ok) {
    throw Object.assign(new Error(`${what} ${shownUrl(url)} could not be fetched (HTTP ${response.status})`), { code: 'bad-file' });
  }
  return { url, response };
}

// A URL as a message names it: the page's own files by their path, another
// site's with its host; a blob: or data: URL by its kind (its path was a
// random id, or the data itself, and the host was dropped).
function shownUrl(url) {
  if (url.protocol === 'blob:' || url.protocol === 'data:') return `(a ${url.protocol} URL)`;
  return url.origin === location.origin ? url.pathname : `${url.host}${url.pathname}`;
}

export async function resolveMeshSource(source, name) {
  if (!isUrl(source)) return { data: source, name: name ?? source?.name };
  const { url, response } = await fetched(source, 'The mesh');
  const fromPath = decodeURIComponent(url.pathname.split('/').pop() ?? '');
  return { data: await response.arrayBuffer(), name: name ?? fromPath };
}

/** An edit document (saved edits), or its URL: the document as JSON. */
export async function resolveDocumentSource(source) {
  if (!isUrl(source)) return source;
  const { url, response } = await fetched(source, 'The edit document');
  const text = await response.text();
  try {
    return JSON.parse(text);
  } catch (error) {
    throw Object.assign(new Error(`The edit document ${shownUrl(url)} is not JSON: ${error.message}`), { code: 'bad-file' });
  }
}
