// + (or =, the same key unshifted) and - zoom the 3D view while it has the
// focus, as the arrow keys pan and Shift+arrows orbit it (OrbitControls has
// keys for those only: a keyboard user could not zoom at all). With Ctrl or
// Cmd the keys stay the browser's page zoom.

// Each press moves the camera this factor nearer to (or farther from) the
// orbit target: about what one notch of a mouse wheel does.
const ZOOM_STEP = 1.2;

export function installKeyboardZoom(viewer, lifetime) {
  lifetime.listen(viewer.canvas, 'keydown', (event) => {
    if (event.ctrlKey || event.metaKey || event.altKey) return;
    const zoomIn = event.key === '+' || event.key === '=';
    if (!zoomIn && event.key !== '-') return;
    event.preventDefault();
    // dollyIn/Out take the wheel's factor below 1 (OrbitControls' getZoomScale).
    if (zoomIn) viewer.controls.dollyIn(1 / ZOOM_STEP);
    else viewer.controls.dollyOut(1 / ZOOM_STEP);
  });
}
