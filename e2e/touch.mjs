// Real touch input for the end-to-end tests: touch events sent through the
// Chrome DevTools Protocol (Input.dispatchTouchEvent), which the browser
// turns into pointer events as it does for a finger on a touch screen. The
// page must be opened with hasTouch.
export async function touchScreen(page) {
  const cdp = await page.context().newCDPSession(page);
  const send = (type, fingers) => cdp.send('Input.dispatchTouchEvent', {
    type,
    touchPoints: fingers.map(([x, y], id) => ({ x, y, id, radiusX: 4, radiusY: 4, force: 1 })),
  });
  return {
    /** Fingers down at page points [[x, y], ...] (all fingers on the screen, the new ones last). */
    start: (fingers) => send('touchStart', fingers),
    move: (fingers) => send('touchMove', fingers),
    /** Every finger lifted. */
    end: () => send('touchEnd', []),
  };
}

/** One finger dragged from `from` by [dx, dy] in `steps` moves, then lifted. */
export async function swipe(screen, from, [dx, dy], steps = 8) {
  await screen.start([from]);
  for (let step = 1; step <= steps; step++) {
    await screen.move([[from[0] + (dx * step) / steps, from[1] + (dy * step) / steps]]);
  }
  await screen.end();
}
