// The worker's side of Teach mode: one `Teacher` (recorder) beside the Session. Loaded by
// worker.ts, which passes in how to replace its Session.
import * as lfd from 'logic-lfd';
import type { Frame } from 'logic-lfd';
import type { TeachApi } from './teach-protocol';

type TeachHandlers = { [K in keyof TeachApi]: (args: TeachApi[K]['args']) => TeachApi[K]['result'] };

let teacher: lfd.Teacher | null = null;

function need(): lfd.Teacher {
  if (!teacher) throw new Error('not recording: press Record first');
  return teacher;
}

/** The Teach handlers; `replace` installs a new Session (stopping the old one) and returns its frame. */
export function teachHandlers(replace: (s: lfd.Session) => Frame): TeachHandlers {
  return {
    teachStart: ({ benchmark, scene }) => {
      const t = new lfd.Teacher(benchmark, scene);
      teacher?.free();
      teacher = t;
      return t.current();
    },
    teachPush: ({ edit }) => need().push(edit),
    teachUndo: () => need().undo(),
    teachFinish: () => need().finish(),
    teachRecording: () => need().recordingJson(),
    teachInfo: ({ demoJson }) => lfd.taughtInfo(demoJson),
    teachRun: ({ demoJson, options }) => replace(lfd.Session.fromTaught(demoJson, options)),
    teachClose: () => {
      teacher?.free();
      teacher = null;
      return null;
    },
  };
}
