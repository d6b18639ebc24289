// The login page: the daemon's token becomes an HttpOnly session cookie (POST /api/session).
import { post } from './api.js';

const form = document.getElementById('login-form');
form.addEventListener('submit', async (event) => {
  event.preventDefault();
  const error = document.getElementById('login-error');
  error.textContent = '';
  try {
    await post('/api/session', { token: document.getElementById('token').value.trim() });
    window.location.href = '/';
  } catch (e) {
    error.textContent = e.message;
  }
});
