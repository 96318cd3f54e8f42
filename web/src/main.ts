import { WorkerClient } from './client';

const client = new WorkerClient(() => {});
const app = document.getElementById('app')!;
client.ready.then(
  (v) => {
    app.dataset.ready = 'true';
    app.innerHTML = `<p id="boot">logic-lfd ${v} loaded in a worker.</p>`;
  },
  (e: Error) => {
    app.innerHTML = `<p id="boot" role="alert">${e.message}</p>`;
  },
);
