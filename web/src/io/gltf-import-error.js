// A glTF the page cannot read: its message names the file and what is wrong.
export class GltfImportError extends Error {
  constructor(message) {
    super(message);
    this.name = 'GltfImportError';
    this.code = 'bad-file';
  }
}
