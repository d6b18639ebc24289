// The stop bar: on every page of the console (one <script type="module" src="/js/stop_bar.js">
// line each), a red STOP button always in reach and Esc, whatever has focus, send POST
// /api/stop. The stop needs no session (daemon_api.cpp, refuse_stop: the console's header and
// a same-origin request are enough, since stopping only makes the bench safer), so it works
// for a console whose session expired or that never logged in. Esc sends the stop whenever it
// is pressed: when nothing moves it is a harmless no-op.
//
// The bar also shows what the bench does, who is logged in (with Log out), and a banner when
// the daemon restarted (GET /api/status "instance" changed) or the session ended.
import { api } from './api.js';

const POLL_MS = 1000;
const SESSION_MS = 60000;

function injectStyle() {
  if (document.querySelector('link[href="/css/stop_bar.css"]')) return;
  const link = document.createElement('link');
  link.rel = 'stylesheet';
  link.href = '/css/stop_bar.css';
  document.head.append(link);
}

function build() {
  const bar = document.createElement('div');
  bar.id = 'stop-bar';
  bar.setAttribute('role', 'region');
  bar.setAttribute('aria-label', 'Stop the bench');
  bar.innerHTML = `
    <button id="stop" type="button" title="Stop the bench: drive off, brake off (Esc on any page)">STOP</button>
    <span class="stop-bar-hint">Esc stops</span>
    <span id="stop-bar-state" role="status">…</span>
    <span id="stop-bar-message" role="status"></span>
    <span id="stop-bar-banner" role="alert" hidden></span>
    <span id="stop-bar-account">
      <span id="stop-bar-who"></span>
      <a id="stop-bar-login" href="/login">Log in</a>
      <a id="stop-bar-logout" href="/login" hidden>Log out</a>
    </span>`;
  document.body.prepend(bar);
  return bar;
}

const $ = (id) => document.getElementById(id);
let instance = null;       // the daemon's instance id when this page first saw it
let wasLoggedIn = false;
let lastState = null;

function localTime(iso) {
  const t = iso ? new Date(iso) : new Date();
  return Number.isNaN(t.getTime()) ? new Date().toLocaleTimeString('en-GB') : t.toLocaleTimeString('en-GB');
}

function banner(text) {
  const b = $('stop-bar-banner');
  b.hidden = !text;
  b.textContent = text || '';
  if (text) {
    const link = document.createElement('a');
    link.href = '/login';
    link.textContent = 'Log in';
    b.append(' ', link);
  }
}

// The manual panel holds the servo or moves the input (/api/status manual, servo in words).
function manualEngaged(s) {
  const m = s.manual || {};
  return !!(m.servo_on || m.jog_rpm || m.goto_deg != null || m.brake_nm > 0);
}

function moving(s) {
  return s.state === 'running' || s.run != null || manualEngaged(s);
}

function describe(s) {
  if (s.run) {
    const pct = typeof s.run.progress === 'number' ? ` ${(100 * s.run.progress).toFixed(0)} %` : '';
    return `running ${s.run.procedure || ''}${pct}`;
  }
  if (s.state === 'fault') return `fault: ${s.fault_reason || ''}`;
  if (s.state === 'stopping') return 'stopping: safe state, back to ready by itself';
  if (manualEngaged(s) || (typeof s.servo === 'string' && s.servo !== 'servo off')) {
    return `manual: ${s.servo || 'servo on'}${s.brake && s.brake !== 'brake off' ? ` · ${s.brake}` : ''}`;
  }
  if (s.state === 'ready') return 'ready: nothing moves';
  return s.state || '?';
}

function showStatus(s) {
  lastState = s;
  const state = $('stop-bar-state');
  state.textContent = describe(s);
  state.className = `state-${s.state}`;
  document.getElementById('stop-bar').classList.toggle('moving', !!moving(s));
  const id = s.instance && s.instance.id;
  if (id && instance && id !== instance) {
    banner(`the daemon restarted at ${localTime(s.instance.started_at)} — log in again (STOP still works)`);
    wasLoggedIn = false;
    checkSession();
  }
  if (id) instance = id;
}

async function pollStatus() {
  try {
    showStatus(await api('GET', '/api/status'));
  } catch (_) {
    $('stop-bar-state').textContent = 'daemon not answering';
    $('stop-bar-state').className = 'state-unknown';
  }
}

function showSession(session) {
  const who = $('stop-bar-who');
  const logged = !!(session && session.authenticated);
  who.textContent = logged
    ? `logged in as ${session.account || 'token'}${session.role ? ` (${session.role})` : ''}`
    : 'not logged in';
  $('stop-bar-login').hidden = logged;
  $('stop-bar-logout').hidden = !logged;
  if (wasLoggedIn && !logged && $('stop-bar-banner').hidden) {
    banner(`session ended at ${localTime()} — log in again (STOP still works)`);
  }
  wasLoggedIn = logged;
}

async function checkSession() {
  try {
    showSession(await api('GET', '/api/session'));
  } catch (_) {
    // the status poll shows a daemon that does not answer
  }
}

export async function stop() {
  const msg = $('stop-bar-message');
  const sent = performance.now();
  try {
    await api('POST', '/api/stop', {});
    msg.textContent = `stop sent (${Math.round(performance.now() - sent)} ms): drive off, brake off`;
    msg.className = '';
  } catch (e) {
    msg.textContent = `STOP failed: ${e.message} — use the hardware emergency stop`;
    msg.className = 'error';
  }
  pollStatus();
}

function install() {
  injectStyle();
  build();
  $('stop').addEventListener('click', stop);
  // Capture phase: a field or a dialog that handles Esc itself still lets the stop through.
  document.addEventListener('keydown', (e) => {
    if (e.key === 'Escape' || e.key === 'Esc') {
      e.preventDefault();
      stop();
    }
  }, true);
  $('stop-bar-logout').addEventListener('click', async (e) => {
    e.preventDefault();
    try {
      await api('DELETE', '/api/session');
    } catch (_) {
      // logged out either way
    }
    wasLoggedIn = false;
    window.location.href = '/login';
  });
  pollStatus();
  checkSession();
  setInterval(pollStatus, POLL_MS);
  setInterval(checkSession, SESSION_MS);
  window.wavebenchStopBar = { stop, status: () => lastState };
}

if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', install);
else install();
