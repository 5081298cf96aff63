// Buttons that are off for a while without losing the keyboard's focus. A
// focused button made `disabled` drops the focus to <body>: Enter on Apply
// started a solve, and the keyboard user was back at the page's top (so were
// Flatten, and Undo at the history's start). These say it with
// aria-disabled instead: still focusable and named "dimmed" by a screen
// reader, drawn as a disabled button, and a click or Enter meanwhile does
// nothing.

/** Turns `button` off (true) or on, keeping it focusable. */
export function setOff(button, off) {
  button.setAttribute('aria-disabled', String(off));
}

/** `handler` for a button that setOff turns off: not called while it is. */
export function whenOn(handler) {
  return (event) => {
    if (event.currentTarget.getAttribute('aria-disabled') === 'true') return undefined;
    return handler(event);
  };
}
