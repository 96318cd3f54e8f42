/**
 * Small DOM helpers shared by the page's panels (no framework: the page is small and must load
 * fast): a typed element builder, labelled buttons and selects, fact-change chips, a demo state's
 * list item, a file download, the keyboard-shortcut filter and the guard that turns a failed UI
 * action into a notice.
 */
type Child = Node | string | null | undefined | false;

export function el<K extends keyof HTMLElementTagNameMap>(
  tag: K,
  attrs: Record<string, string> = {},
  ...children: Child[]
): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class') e.className = v;
    else if (k === 'hidden') e.hidden = true;
    else e.setAttribute(k, v);
  }
  for (const c of children) if (c !== null && c !== undefined && c !== false) e.append(c);
  return e;
}

/** A button whose label is both its accessible name and its tooltip. */
export function button(id: string, label: string, text: string, cls = ''): HTMLButtonElement {
  return el('button', { id, 'aria-label': label, title: label, class: cls, type: 'button' }, text);
}

/** A labelled select of `[value, text]` items, set to `value`. */
export function select<T extends string>(id: string, label: string, items: [T, string, ...unknown[]][], value: T): HTMLSelectElement {
  const s = el('select', { id, 'aria-label': label, title: label }, ...items.map(([v, t]) => el('option', { value: v }, t)));
  s.value = value;
  return s;
}

/** Chips for the facts a change added (+) and removed (−). */
export function factChips(added: string[], removed: string[]): HTMLElement[] {
  return [...added.map((x) => el('span', { class: 'chip added' }, `+ ${x}`)), ...removed.map((x) => el('span', { class: 'chip removed' }, `− ${x}`))];
}

/** L_k as the paper writes it (k a subscript), so a demonstration state never reads like a
 * disturbance level. */
export function lk(k: number | string, base = 'L'): HTMLElement {
  return el('span', { class: 'lk' }, base, el('sub', {}, String(k)));
}

/** L_k as plain text, k in subscript digits (for sentences and tooltips). */
export const lkText = (k: number): string => `L${[...String(k)].map((d) => '₀₁₂₃₄₅₆₇₈₉'[Number(d)]).join('')}`;

/** The list item of demo state L`i` (its facts in the tooltip). */
export function demoStateItem(i: number, facts: string[], cls = 'demo-state'): HTMLLIElement {
  return el('li', { class: cls, title: facts.join(' ') }, lk(i), el('span', { class: 'muted' }, ` · ${facts.length} facts`));
}

/** Saves `text` as a JSON file named `name` (the browser's download). */
export function downloadJson(text: string, name: string): void {
  const a = el('a', { href: URL.createObjectURL(new Blob([text], { type: 'application/json' })), download: name });
  a.click();
  URL.revokeObjectURL(a.href);
}

/** Whether a key press is for the page's shortcuts: not typed into a field or the editor, and
 * without Ctrl, Meta or Alt (those belong to the browser). */
export function isShortcut(e: KeyboardEvent): boolean {
  const t = e.target as HTMLElement;
  if (t.closest('.cm-editor') || t instanceof HTMLInputElement || t instanceof HTMLSelectElement) return false;
  return !(e.ctrlKey || e.metaKey || e.altKey);
}

/** The message of anything thrown. */
export function errorText(e: unknown): string {
  return e instanceof Error ? e.message : String(e);
}

/** Runs a UI action; a failure (no session, a refused request) is reported, never thrown. */
export async function guard(f: () => unknown, report: (message: string) => void): Promise<void> {
  try {
    await f();
  } catch (e) {
    report(errorText(e));
  }
}
