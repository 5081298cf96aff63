// Number fields as text inputs with a decimal keypad. A decimal comma, as
// much of Europe types it ("1,5"), is read as a point: an <input
// type=number> in Chromium dropped the comma and handed back "15", a silent
// tenfold stretch. Anything else that is not a plain decimal number (text,
// "1,000.5", an empty field) is no value.
import { h } from './dom.js';

const DECIMAL = /^[+-]?(\d+\.?\d*|\.\d+)(e[+-]?\d+)?$/i;

/** The number `text` means, or NaN. */
export function parseDecimal(text) {
  const trimmed = String(text ?? '').trim();
  const pointed = /^[^.,]*,[^.,]*$/.test(trimmed) ? trimmed.replace(',', '.') : trimmed;
  return DECIMAL.test(pointed) ? Number(pointed) : NaN;
}

/** An <input> for a number (`props` as h() takes them): text, with a decimal keypad on phones. */
export function decimalInput(props = {}) {
  return h('input', { type: 'text', inputMode: 'decimal', autocomplete: 'off', spellcheck: false, ...props });
}
