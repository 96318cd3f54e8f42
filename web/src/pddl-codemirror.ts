/**
 * CodeMirror 6 set-up shared by the PDDL tab's editors (domain, problem, demonstration, the
 * current state): PDDL highlighting, the dark theme, and inline lint diagnostics placed at the
 * 1-based line:col the wasm parser reports.
 */
import { EditorState, type Extension } from '@codemirror/state';
import { EditorView, keymap, lineNumbers, highlightActiveLine, drawSelection } from '@codemirror/view';
import { defaultKeymap, history, historyKeymap } from '@codemirror/commands';
import { StreamLanguage, syntaxHighlighting, HighlightStyle, bracketMatching } from '@codemirror/language';
import { linter, lintGutter, setDiagnostics, type Diagnostic as CmDiagnostic } from '@codemirror/lint';
import { tags as t } from '@lezer/highlight';

const pddl = StreamLanguage.define<{ depth: number }>({
  name: 'pddl',
  startState: () => ({ depth: 0 }),
  token(stream, state) {
    if (stream.eatSpace()) return null;
    const ch = stream.peek();
    if (ch === ';') {
      stream.skipToEnd();
      return 'comment';
    }
    if (ch === '(' || ch === ')') {
      stream.next();
      state.depth += ch === '(' ? 1 : -1;
      return 'paren';
    }
    if (ch === ':') {
      if (!stream.match(/^:[\w-]+/)) stream.next();
      return 'keyword';
    }
    if (ch === '?') {
      if (!stream.match(/^\?[\w-]+/)) stream.next();
      return 'variableName';
    }
    if (ch === '-' && stream.match(/^-\s/, false)) {
      stream.next();
      return 'operator';
    }
    if (stream.match(/^-?\d+(\.\d+)?/)) return 'number';
    if (stream.match(/^(define|domain|problem|and|or|not|imply|forall|exists|when|either|increase)\b/i)) return 'keyword';
    if (!stream.match(/^[^\s();]+/)) stream.next();
    return 'atom';
  },
});

const highlight = HighlightStyle.define([
  { tag: t.comment, color: '#6b7686', fontStyle: 'italic' },
  { tag: t.keyword, color: '#7aa2f7' },
  { tag: t.variableName, color: '#e0af68' },
  { tag: t.number, color: '#ff9e64' },
  { tag: t.atom, color: '#c9d1d9' },
  { tag: t.paren, color: '#6b7686' },
  { tag: t.operator, color: '#bb9af7' },
]);

const theme = EditorView.theme(
  {
    '&': { height: '100%', fontSize: '12.5px', backgroundColor: '#0f1216' },
    '.cm-content': { fontFamily: 'ui-monospace, SFMono-Regular, Menlo, Consolas, monospace', caretColor: '#e6edf3' },
    '.cm-gutters': { backgroundColor: '#0f1216', color: '#4d5662', border: 'none' },
    '.cm-activeLine': { backgroundColor: '#161b22' },
    '.cm-activeLineGutter': { backgroundColor: '#161b22' },
    '&.cm-focused .cm-cursor': { borderLeftColor: '#e6edf3' },
    '.cm-selectionBackground, &.cm-focused .cm-selectionBackground': { backgroundColor: '#264f78 !important' },
    '.cm-scroller': { overflow: 'auto' },
  },
  { dark: true },
);

/** A located message for one editor (1-based line and column; line 0: not about a place). */
export interface Located {
  line: number;
  col: number;
  message: string;
}

/** A PDDL editor in `parent`, labelled `label` for assistive technology; `onChange` on every edit. */
export function pddlEditor(parent: HTMLElement, label: string, onChange: () => void): EditorView {
  const extensions: Extension[] = [
    lineNumbers(),
    history(),
    drawSelection(),
    highlightActiveLine(),
    bracketMatching(),
    EditorView.lineWrapping,
    pddl,
    syntaxHighlighting(highlight),
    lintGutter(),
    linter(null),
    theme,
    keymap.of([...defaultKeymap, ...historyKeymap]),
    EditorView.contentAttributes.of({ 'aria-label': label }),
    EditorView.updateListener.of((u) => {
      if (u.docChanged) onChange();
    }),
  ];
  return new EditorView({ state: EditorState.create({ doc: '', extensions }), parent });
}

/** The document offset of 1-based `line`:`col`, clamped into the document. */
export function offsetOf(doc: EditorState['doc'], line: number, col: number): number {
  const l = doc.line(Math.min(Math.max(1, line), doc.lines));
  return Math.min(l.from + Math.max(0, col - 1), l.to);
}

/** Shows `diags` (those with a place) as the editor's inline errors, replacing the previous ones. */
export function lint(v: EditorView, diags: Located[]): void {
  const mine: CmDiagnostic[] = diags
    .filter((d) => d.line > 0)
    .map((d) => {
      const from = offsetOf(v.state.doc, d.line, d.col);
      return { from, to: Math.min(from + 1, v.state.doc.length), severity: 'error', message: d.message };
    });
  v.dispatch(setDiagnostics(v.state, mine));
}

/** Replaces the whole text of `v`. */
export function setText(v: EditorView, text: string): void {
  v.dispatch({ changes: { from: 0, to: v.state.doc.length, insert: text } });
}

/** Puts the cursor at `line`:`col` of `v`, scrolls there and focuses the editor. */
export function revealAt(v: EditorView, line: number, col: number): void {
  const pos = offsetOf(v.state.doc, line, col);
  v.dispatch({ selection: { anchor: pos }, scrollIntoView: true });
  v.focus();
}
