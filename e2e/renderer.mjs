// Which CPU rasteriser the end-to-end browser draws WebGL with: one place,
// read by the Playwright config (the launch flags) and by the test that
// checks the page really got it (a missing Mesa package would otherwise fall
// back to SwiftShader silently and change every measured rate).
//
// Default: Mesa's llvmpipe through ANGLE's OpenGL ES over EGL backend
// (scripts/setup.sh installs libegl-mesa0 and libgl1-mesa-dri). Why: both
// renderers run on the CPU, but presenting a frame is what bounds a headless
// page's frame rate, and SwiftShader's compositor swap costs 52-78 ms a frame
// at the suite's 900x600 (a Chrome trace), whatever the page draws: the same
// 20k-vertex slider (document.spec) showed 13-15 frames with new positions a
// second under SwiftShader and 18-28 under llvmpipe. ANISO_E2E_RENDERER=swiftshader runs the suite
// on ANGLE's SwiftShader instead, as Chromium picks on a machine without GPU.
const RENDERERS = {
  llvmpipe: { args: ['--use-gl=angle', '--use-angle=gl-egl', '--ignore-gpu-blocklist'], name: /llvmpipe/i },
  swiftshader: { args: ['--use-angle=swiftshader', '--ignore-gpu-blocklist'], name: /swiftshader/i },
};

const chosen = process.env.ANISO_E2E_RENDERER ?? 'llvmpipe';
if (!(chosen in RENDERERS)) {
  throw new Error(`ANISO_E2E_RENDERER='${chosen}': use ${Object.keys(RENDERERS).join(' or ')}`);
}

export const rendererName = chosen;
/** Chromium flags that select the renderer (GPU compositing on it, as a desktop browser does). */
export const rendererArgs = RENDERERS[chosen].args;
/** What WEBGL_debug_renderer_info reports for it. */
export const rendererPattern = RENDERERS[chosen].name;
