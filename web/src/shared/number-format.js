// How the app writes numbers for people: one style everywhere, the one its
// number fields show and read (a decimal point, en-US digit groups). The
// status bar, selection panel and announcer used toLocaleString(), which in
// German says "2.930" for 2930 beside fields and an Edits list that wrote
// "2,930" and "1.5": the same figure in two notations on one screen.

const COUNT = new Intl.NumberFormat('en-US', { maximumFractionDigits: 0 });

/** A whole count with digit groups: 2930 -> "2,930". */
export function formatCount(value) {
  return COUNT.format(value);
}

/** A fraction as a percentage, two decimals under 1 %: 0.0123 -> "1.2 %". */
export function formatPercent(value) {
  if (!Number.isFinite(value)) return '—';
  return `${(100 * value).toFixed(value < 0.01 ? 2 : 1)} %`;
}
