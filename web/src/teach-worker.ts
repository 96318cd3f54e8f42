/**
 * The worker's side of Teach mode: one `Teacher` (recorder) beside the Session. Loaded by
 * worker.ts, which passes in how to replace its Session. The recorder lives in the full wasm
 * module ('logic-lfd-teach'; it also has `Session.replay`), which is not part of the page's first
 * load: it is fetched and compiled the first time it is needed (`teachLoad` when the tab opens).
 */
import type { Frame } from 'logic-lfd';
import type { TeachApi } from './teach-protocol';

type TeachModule = typeof import('logic-lfd-teach');
type TeachHandlers = {
  [K in keyof TeachApi]: (args: TeachApi[K]['args']) => TeachApi[K]['result'] | Promise<TeachApi[K]['result']>;
};

let loading: Promise<TeachModule> | null = null;
let loaded: TeachModule | null = null;
let memory: WebAssembly.Memory | null = null;
/** Its size when it was instantiated (bytes). */
let freshBytes = 0;
let teacher: InstanceType<TeachModule['Teacher']> | null = null;

/** The full module, instantiated once (a failed fetch is retried on the next call). */
export function teachModule(): Promise<TeachModule> {
  loading ??= import('logic-lfd-teach').then(
    async (m) => {
      memory = (await m.default()).memory;
      freshBytes = memory.buffer.byteLength;
      loaded = m;
      return m;
    },
    (e: unknown) => {
      loading = null;
      throw e;
    },
  );
  return loading;
}

function need(): InstanceType<TeachModule['Teacher']> {
  if (!teacher) throw new Error('not recording: press Record first');
  return teacher;
}

/** The last panic of the Teach module, or "" (not loaded, or no panic). */
export function teachLastPanic(): string {
  return loaded?.lastPanic() ?? '';
}

/** The Teach module's wasm memory in bytes, now and when it was instantiated (0 until it is loaded). */
export function teachMemoryBytes(): [number, number] {
  return [memory?.buffer.byteLength ?? 0, freshBytes];
}

/** The Teach handlers; `replace` installs a new Session (stopping the old one) and returns its frame. */
export function teachHandlers(replace: (s: InstanceType<TeachModule['Session']>) => Frame): TeachHandlers {
  return {
    teachLoad: () => {
      void teachModule().catch(() => {}); // a failure is reported by the call that needs the module
      return null;
    },
    teachStart: async ({ benchmark, folder }) => {
      const m = await teachModule();
      const t = folder ? m.Teacher.fromFolder(folder.files, { dir: folder.dir }) : new m.Teacher(benchmark);
      teacher?.free();
      teacher = t;
      return t.current();
    },
    teachPush: ({ edit }) => need().push(edit),
    teachUndo: () => need().undo(),
    teachFinish: () => need().finish(),
    teachRecording: () => need().recordingJson(),
    teachInfo: async ({ demoJson, folder }) => (await teachModule()).taughtInfo(demoJson, folder),
    teachRun: async ({ demoJson, options, folder }) => replace((await teachModule()).Session.fromTaught(demoJson, options, folder)),
    teachClose: () => {
      teacher?.free();
      teacher = null;
      return null;
    },
  };
}
