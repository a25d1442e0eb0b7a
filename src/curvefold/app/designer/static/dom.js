// Building the page's elements: text always goes in as text, never parsed as HTML.

/** The element of an id. */
export const byId = (id) => document.getElementById(id);

const asNode = (child) => (child instanceof Node ? child : String(child));

/**
 * A new element: `props` are set as its properties (`dataset` and `style` merged in), and
 * `children` appended (strings and numbers as text; null, undefined and false left out).
 */
export function el(tag, props = {}, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(props)) {
    if (value === undefined || value === null) continue;
    if (key === "dataset" || key === "style") Object.assign(node[key], value);
    else node[key] = value;
  }
  node.append(...children.filter((c) => c !== null && c !== undefined && c !== false).map(asNode));
  return node;
}
