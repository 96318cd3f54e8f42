/**
 * Permalinks of the PDDL tab: the domain, problem and demonstration texts deflated into the URL's
 * `#pddl=` hash (base64url), and read back on load. Loaded on demand, never on the first load.
 */
import { deflateSync, inflateSync, strFromU8, strToU8 } from 'fflate';

export interface PddlTexts {
  domain: string;
  problem: string;
  demo: string;
}

const PREFIX = '#pddl=';

function toBase64Url(bytes: Uint8Array): string {
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(s).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

function fromBase64Url(text: string): Uint8Array {
  const s = atob(text.replace(/-/g, '+').replace(/_/g, '/'));
  return Uint8Array.from(s, (c) => c.charCodeAt(0));
}

/** The page's address with `texts` in its hash. */
export function linkFor(texts: PddlTexts): string {
  const packed = deflateSync(strToU8(JSON.stringify([texts.domain, texts.problem, texts.demo])), { level: 9 });
  return `${location.origin}${location.pathname}${location.search}${PREFIX}${toBase64Url(packed)}`;
}

/** The texts a `#pddl=` hash carries; null when there is none or it does not read. */
export function textsFromHash(hash: string): PddlTexts | null {
  if (!hash.startsWith(PREFIX)) return null;
  try {
    const v: unknown = JSON.parse(strFromU8(inflateSync(fromBase64Url(hash.slice(PREFIX.length)))));
    if (!Array.isArray(v) || v.length !== 3 || !v.every((t) => typeof t === 'string')) return null;
    const [domain, problem, demo] = v as string[];
    return { domain, problem, demo };
  } catch {
    return null;
  }
}

/** Opens the PDDL tab with the texts of the page's hash (a shared link). */
export async function restore(open: (domain: string, problem: string, demo: string) => Promise<void>): Promise<void> {
  const t = textsFromHash(location.hash);
  if (t) await open(t.domain, t.problem, t.demo);
}
