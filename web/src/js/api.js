// The daemon's JSON API as the console uses it. Every request is same-origin and carries the
// X-Wavebench-Request header: a cross-site form cannot send a custom header, and the daemon
// answers no CORS preflight, so only this console's own pages can change the bench.
export class ApiError extends Error {
  constructor(status, body) {
    super((body && (body.detail || body.error)) || `HTTP ${status}`);
    this.status = status;
    this.body = body || {};
  }
  // The option key an API message names ("static.positions: got ..." -> "positions").
  get key() {
    const m = /^(?:[a-z-]+\.)?([A-Za-z0-9_]+)(?:\[\d+\])?:/.exec(this.body.detail || '');
    return m ? m[1] : null;
  }
}

export async function api(method, path, body) {
  const init = {
    method,
    credentials: 'same-origin',
    headers: { 'X-Wavebench-Request': 'console', Accept: 'application/json' },
  };
  if (body !== undefined) {
    init.headers['Content-Type'] = 'application/json';
    init.body = JSON.stringify(body);
  }
  const response = await fetch(path, init);
  let json = null;
  try {
    json = await response.json();
  } catch (_) {
    json = null;
  }
  if (!response.ok) throw new ApiError(response.status, json);
  return json;
}

export const get = (path) => api('GET', path);
export const post = (path, body) => api('POST', path, body === undefined ? {} : body);
