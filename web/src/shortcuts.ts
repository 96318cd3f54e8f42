/**
 * The page's keyboard shortcuts (listed in the help overlay): playback, disturbances, benchmark,
 * speed, the PDDL tab and the help itself. Keys typed into a field or the editor are left alone.
 */
import { isShortcut } from './dom';
import type { HelpOverlay } from './help';
import type { Controls, Stage } from './layout';
import { catalogue } from './catalogue';
import type { SessionControls } from './session-controls';
import type { Tabs } from './tabs';

/** Keys of the Run that would act on the hidden episode while Teach mode owns the view (digits:
 * the disturbance levels). */
const RUN_KEYS = ' nrc123456789';

/** The disturbance level key `k` injects: `1` the catalogue's first, and so on. */
const levelOfKey = (k: string) => (/^[1-9]$/.test(k) ? catalogue()?.levels[Number(k) - 1]?.id : undefined);

export function installShortcuts(p: { help: HelpOverlay; session: SessionControls; tabs: Tabs; controls: Controls; stage: Stage }): void {
  const { help, session, tabs } = p;
  const act: Record<string, () => void> = {
    ' ': () => void session.togglePlay(),
    n: () => p.controls.stepBtn.click(),
    r: () => void session.guard(() => session.reset()),
    c: () => p.stage.cancelBtn.click(),
    b: () => session.nextBenchmark(),
    '+': () => session.stepSpeed(1),
    '=': () => session.stepSpeed(1),
    '-': () => session.stepSpeed(-1),
    p: () => tabs.select('pddl'),
    '?': () => help.open(),
  };
  // A Space released on a bar button would press it (the keydown below already acted).
  document.addEventListener('keyup', (e) => {
    if (spaceOnTopBar(e)) e.preventDefault();
  });
  document.addEventListener('keydown', (e) => {
    if (spaceOnTopBar(e)) {
      // Space means play / pause even right after a select or a button of the bar was used
      // (it would open the select or press the button again).
      e.preventDefault();
      if (!help.shown && !tabs.teach?.active) void session.togglePlay();
      return;
    }
    if (!isShortcut(e)) return;
    if (e.key === 'Escape' && help.shown) return help.close();
    if (help.shown) return;
    const k = e.key.toLowerCase();
    if (tabs.teach?.active && RUN_KEYS.includes(k)) return;
    const level = levelOfKey(k);
    const f = level ? () => void session.inject(level) : act[k];
    if (f) {
      e.preventDefault();
      f();
    }
  });
}

/** Whether `e` is a plain Space on a select or a button of the top bar. */
function spaceOnTopBar(e: KeyboardEvent): boolean {
  const t = e.target as HTMLElement;
  if (e.key !== ' ' || e.ctrlKey || e.metaKey || e.altKey || !t.closest?.('.topbar')) return false;
  return t instanceof HTMLSelectElement || t instanceof HTMLButtonElement;
}
