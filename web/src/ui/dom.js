// A tiny DOM builder: h('button', {className: 'x', onclick}, 'Label').
// Keys starting with "on" become listeners, "dataset"/"style" objects merge,
// everything else is set as a property (or an attribute for aria-*/data-*).
export function h(tag, props = {}, ...children) {
  const element = document.createElement(tag);
  for (const [key, value] of Object.entries(props ?? {})) {
    if (value === undefined || value === null) continue;
    if (key.startsWith('on') && typeof value === 'function') element.addEventListener(key.slice(2), value);
    else if (key === 'dataset' || key === 'style') Object.assign(element[key], value);
    else if (key.startsWith('aria-') || key.startsWith('data-') || key === 'for') element.setAttribute(key, value);
    else element[key] = value;
  }
  for (const child of children.flat()) {
    if (child === null || child === undefined || child === false) continue;
    element.append(child instanceof Node ? child : String(child));
  }
  return element;
}

/** A titled, collapsible-free panel section. */
export function section(title, ...children) {
  return h('section', { className: 'panel-section' }, h('h2', {}, title), ...children);
}
