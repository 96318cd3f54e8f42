/**
 * The catalogue of methods, multi-goal modes, benchmarks and disturbance levels (id, label,
 * one-line description) as the wasm module's `catalogue()` gives it. The worker sends it with its
 * `ready` message; the selects, the disturbance buttons, the Compare table, the tooltips and the help
 * are built from it, so none of them names an entry itself.
 */
import type { Catalogue, CatalogueEntry } from 'logic-lfd';

let current: Catalogue | null = null;
let resolveReady!: (c: Catalogue) => void;

/** Resolves with the catalogue once the worker has sent it. */
export const catalogueReady: Promise<Catalogue> = new Promise((res) => (resolveReady = res));

/** Takes the catalogue the worker sent. */
export function setCatalogue(c: Catalogue): void {
  current = c;
  resolveReady(c);
}

/** The catalogue, or null before the worker sent it. */
export function catalogue(): Catalogue | null {
  return current;
}

/** The entries as a select's `[id, label]` items. */
export const items = <T extends string>(entries: CatalogueEntry<T>[]): [T, string][] => entries.map((e) => [e.id, e.label]);

/** The entry of `id`, if `entries` has one. */
export const entryOf = <T extends string>(entries: CatalogueEntry<T>[], id: string | null | undefined): CatalogueEntry<T> | undefined =>
  entries.find((e) => e.id === id);

/** A disturbance level's name on the page (its catalogue label, before the catalogue its id). */
export const levelName = (id: string): string => entryOf(current?.levels ?? [], id)?.label ?? id.toUpperCase();

/** A core message about level `level` ("L3: moved c …") without its level. */
export const withoutLevel = (level: string, m: string): string => m.replace(new RegExp(`^${level}:\\s*`, 'i'), '');

/** A core message about level `level`, led by the level's name on the page ("Scramble: moved c …"). */
export const withLevel = (level: string, m: string): string => `${levelName(level)}: ${withoutLevel(level, m)}`;

/** The one-line description of `id` ('' for an unknown id). */
export const descriptionOf = <T extends string>(entries: CatalogueEntry<T>[], id: string): string => entryOf(entries, id)?.description ?? '';
