/**
 * The goal of the current task in words (from the problem's `:goal`, or for a generated tower
 * from the demonstration's last state), for the Run tab and the first-visit hint (hint.ts).
 */

/** The facts inside a problem's `(:goal …)`, as `(pred arg …)` strings. */
export function goalFacts(problem: string): string[] {
  const i = problem.indexOf(':goal');
  if (i < 0) return [];
  return [...problem.slice(i).matchAll(/\((?!and\b|or\b|not\b)[a-z][\w-]*(?:\s+[\w-]+)*\)/gi)].map((m) => m[0].replace(/\s+/g, ' '));
}

/** One fact in words: `(on a b)` → "a on b", `(onshelf a)` → "a on the shelf". */
export function factWords(fact: string): string {
  const [p, ...args] = fact.slice(1, -1).split(' ');
  if ((p === 'on' || p === 'on-block') && args.length === 2) return `${args[0]} on ${args[1]}`;
  if (p === 'onshelf' && args.length === 1) return `${args[0]} on the shelf`;
  if ((p === 'ontable' || p === 'on-table') && args.length === 1) return `${args[0]} on the table`;
  if (p === 'at' && args.length === 2) return `${args[0]} at ${args[1]}`;
  return fact;
}

/** The goal in words: "a on b, b on c and c on d". */
export function goalWords(facts: string[]): string {
  const w = facts.map(factWords);
  return w.length > 1 ? `${w.slice(0, -1).join(', ')} and ${w[w.length - 1]}` : (w[0] ?? '');
}
