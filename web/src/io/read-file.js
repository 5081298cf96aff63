// Reads a File or Blob into an ArrayBuffer, reporting progress (a fraction in
// [0, 1]) so big uploads show a moving bar.
export function readFileBytes(blob, onProgress) {
  return new Promise((resolve, reject) => {
    const reader = new FileReader();
    reader.onprogress = (event) => {
      if (event.lengthComputable && event.total > 0) onProgress?.(event.loaded / event.total);
    };
    reader.onload = () => resolve(reader.result);
    reader.onerror = () => reject(new Error(`The file could not be read: ${reader.error?.message ?? 'unknown error'}`));
    reader.readAsArrayBuffer(blob);
  });
}
