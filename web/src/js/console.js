// Placeholder: the bench console (panel, live plots, start form, stop, progress) goes here.
import { get } from './api.js';

get('/api/status').then((s) => {
  document.getElementById('state').textContent = s.lifecycle;
});
