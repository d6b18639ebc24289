// Reads of run data as the daemon allows them: at most two in flight (it serves two at once
// and answers 503 "busy" to a third), each refused read retried with a growing pause. A busy
// daemon is load, not an error: the page waits instead of showing it.
import { get, ApiError } from './api.js';

const MAX_IN_FLIGHT = 2;
const RETRY_FOR_MS = 120000;
const waiting = [];
let inFlight = 0;

function next() {
  while (inFlight < MAX_IN_FLIGHT && waiting.length) {
    const job = waiting.shift();
    inFlight += 1;
    job().finally(() => { inFlight -= 1; next(); });
  }
}

const pause = (ms) => new Promise((resolve) => { setTimeout(resolve, ms); });

export const isBusy = (e) => e instanceof ApiError && e.status === 503;

// Runs `read` (a function returning a promise) in the queue, retrying while the daemon is busy.
export function queued(read) {
  return new Promise((resolve, reject) => {
    const started = Date.now();
    let delay = 200;
    const attempt = async () => {
      try {
        resolve(await read());
      } catch (e) {
        if (!isBusy(e) || Date.now() - started > RETRY_FOR_MS) { reject(e); return; }
        await pause(delay + Math.random() * 100);
        delay = Math.min(delay * 2, 3000);
        waiting.unshift(attempt);  // its turn again first: the order of the reads is kept
      }
    };
    waiting.push(attempt);
    next();
  });
}

export const readRun = (path) => queued(() => get(path));

// A download (export) through the same queue: the bytes, or the daemon's message on refusal.
export function fetchFile(path) {
  return queued(async () => {
    const response = await fetch(path, { credentials: 'same-origin', headers: { 'X-Wavebench-Request': 'console' } });
    if (!response.ok) {
      let body = null;
      try { body = await response.json(); } catch (_) { body = null; }
      throw new ApiError(response.status, body);
    }
    return { blob: await response.blob(), samples: response.headers.get('X-Wavebench-Samples') };
  });
}
