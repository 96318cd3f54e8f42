/**
 * The tooltips of the method and mode selects and of their options: each entry's one-line
 * description from the catalogue (set once the page is ready: this is a chunk of its own).
 */
import type { Catalogue, CatalogueEntry } from 'logic-lfd';
import { descriptionOf } from './catalogue';

/** Gives each option of `sel` its one-line description as a tooltip, and the select the chosen
 * one's (kept up to date on change). */
function explain<T extends string>(sel: HTMLSelectElement, entries: CatalogueEntry<T>[], label: string): void {
  for (const o of sel.options) o.title = descriptionOf(entries, o.value);
  const update = () => (sel.title = `${label}: ${descriptionOf(entries, sel.value)}`);
  sel.addEventListener('change', update);
  update();
}

/** The tooltips of the method and mode selects. */
export function explainSelects(method: HTMLSelectElement, mode: HTMLSelectElement, c: Catalogue): void {
  explain(method, c.methods, 'Method');
  explain(mode, c.modes, 'Multi-goal mode');
}
