/**
 * A PDDL problem text with another initial state: the `(:init …)` section replaced by given atoms,
 * keeping the numeric assignments `(= (f) v)` of the original (action costs). The state editor
 * applies one action to an arbitrary state S_C this way: it asks for the state after that action
 * from a problem whose initial state is S_C.
 */

/** Where the `(:init …)` section is: `[open, close]` indices of its parentheses. */
function initSection(text: string): [number, number] | null {
  let depth = 0;
  let start = -1;
  for (let i = 0; i < text.length; i++) {
    const ch = text[i];
    if (ch === ';') {
      const nl = text.indexOf('\n', i);
      if (nl < 0) break;
      i = nl;
    } else if (ch === '(') {
      if (start < 0 && depth === 1 && /^\(\s*:init(?![\w-])/i.test(text.slice(i, i + 32))) start = i;
      depth++;
    } else if (ch === ')') {
      depth--;
      if (start >= 0 && depth === 1) return [start, i];
    }
  }
  return null;
}

/** The top-level `(= …)` entries between `from` and `to` of `text`, verbatim. */
function numericEntries(text: string, from: number, to: number): string[] {
  const out: string[] = [];
  let depth = 0;
  let open = -1;
  for (let i = from; i < to; i++) {
    const ch = text[i];
    if (ch === ';') {
      const nl = text.indexOf('\n', i);
      i = nl < 0 ? to : nl;
    } else if (ch === '(') {
      if (depth === 0) open = i;
      depth++;
    } else if (ch === ')') {
      depth--;
      if (depth === 0 && open >= 0) {
        const entry = text.slice(open, i + 1);
        if (/^\(\s*=/.test(entry)) out.push(entry);
      }
    }
  }
  return out;
}

/**
 * `problem` with its initial state replaced by `atoms` (e.g. `(on a b)`); `null` when the text has
 * no `(:init …)` section.
 */
export function withInit(problem: string, atoms: string[]): string | null {
  const at = initSection(problem);
  if (!at) return null;
  const [open, close] = at;
  const body = problem.slice(open + 1, close).replace(/^\s*:init/i, '');
  const numeric = numericEntries(body, 0, body.length);
  const lines = [...atoms, ...numeric].map((a) => `    ${a}`).join('\n');
  return `${problem.slice(0, open)}(:init\n${lines})${problem.slice(close + 1)}`;
}

/** The atoms of the `(:init …)` section (not the `(= …)` values), spaces normalised; null without one. */
export function initAtoms(problem: string): string[] | null {
  const at = initSection(problem);
  if (!at) return null;
  const body = problem.slice(at[0] + 1, at[1]).replace(/^\s*:init/i, '');
  const out: string[] = [];
  let depth = 0;
  let open = -1;
  for (let i = 0; i < body.length; i++) {
    const ch = body[i];
    if (ch === ';') {
      const nl = body.indexOf('\n', i);
      i = nl < 0 ? body.length : nl;
    } else if (ch === '(') {
      if (depth === 0) open = i;
      depth++;
    } else if (ch === ')') {
      depth--;
      if (depth === 0 && open >= 0) {
        const atom = body.slice(open, i + 1).replace(/\s+/g, ' ').replace(/\( /g, '(').replace(/ \)/g, ')').toLowerCase();
        if (!/^\(=/.test(atom)) out.push(atom);
      }
    }
  }
  return out;
}
