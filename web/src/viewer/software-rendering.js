// Whether this browser's WebGL draws on the CPU (SwiftShader, llvmpipe,
// Microsoft Basic Render Driver: a machine without a usable GPU, a VM, or
// headless Chromium). There multisampled antialiasing about doubles the cost
// of every frame of a 20k-vertex mesh, which halves how often a live preview
// can show a new shape; a GPU antialiases for free. Asked once per page with
// a throwaway context, before the viewer creates its own.
const SOFTWARE_RENDERERS = /swiftshader|llvmpipe|softpipe|software|basic render/i;

let cached = null;

/** The WebGL renderer's name as the browser reports it ('' when it will not say). */
function rendererName() {
  const canvas = document.createElement('canvas');
  const gl = canvas.getContext('webgl2') ?? canvas.getContext('webgl');
  if (!gl) return '';
  const debugInfo = gl.getExtension('WEBGL_debug_renderer_info');
  const name = String(gl.getParameter(debugInfo ? debugInfo.UNMASKED_RENDERER_WEBGL : gl.RENDERER) ?? '');
  // Browsers allow only a few live contexts per page: give this one back now.
  gl.getExtension('WEBGL_lose_context')?.loseContext();
  return name;
}

export function rendersInSoftware() {
  cached ??= SOFTWARE_RENDERERS.test(rendererName());
  return cached;
}
