// Test fixtures for load errors, shared by the node and browser tests.

/** `value` pretty-printed with `x` set at the key path `keys`, and the line and column where the
 * parser stops on it (the last character of the value, as serde_json reports).
 * @param {any} value
 * @param {(string | number)[]} keys
 * @param {unknown} x
 */
export function withValueAt(value, keys, x) {
  const v = structuredClone(value);
  let o = v;
  for (const k of keys.slice(0, -1)) o = o[k];
  o[keys[keys.length - 1]] = x;
  const text = JSON.stringify(v, null, 2);
  const needle = JSON.stringify(x);
  const lines = text.split('\n');
  const i = lines.findIndex((l) => l.includes(needle));
  return { text, line: i + 1, column: lines[i].indexOf(needle) + needle.length };
}
