// The login page: an operator's name and password (or the daemon's token) become an HttpOnly
// session cookie (POST /api/session). Too many failures: the daemon answers 429 with the wait.
import { get, post } from './api.js';

function attempt(formId, errorId, body) {
  document.getElementById(formId).addEventListener('submit', async (event) => {
    event.preventDefault();
    const error = document.getElementById(errorId);
    error.textContent = '';
    try {
      await post('/api/session', body());
      window.location.href = '/';
    } catch (e) {
      error.textContent = e.message;
    }
  });
}

attempt('account-form', 'account-error', () => ({
  name: document.getElementById('name').value.trim(),
  password: document.getElementById('password').value,
}));
attempt('login-form', 'login-error', () => ({ token: document.getElementById('token').value.trim() }));

// A daemon without an accounts file: only the token logs in (its form stays open); with one,
// the name and password come first and the token folds away.
get('/api/session').then((s) => {
  if (s && s.accounts === false) {
    document.getElementById('account-form').hidden = true;
    document.querySelector('#token-login summary').textContent =
      "Log in with the daemon's token (this daemon has no operator accounts: wavebenchd --accounts)";
    document.getElementById('token').focus();
  } else if (s && s.accounts === true) {
    document.getElementById('token-login').open = false;
  }
}).catch(() => {});
