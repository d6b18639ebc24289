// The run page's export buttons: the run's samples as MATLAB .mat, HDF5, CSV or JSON
// (GET /api/runs/{id}/export?format=...). Each link downloads on its own (a plain href, so it
// also works from a bookmark); a click goes through the read queue, so a busy daemon is waited
// for instead of saving its refusal as the file.
import { el } from './dom.js';
import { fetchFile } from './run_reads.js';

export const EXPORT_FORMATS = [
  { format: 'mat', label: '.mat (MATLAB, Octave)', file: 'mat' },
  { format: 'hdf5', label: 'HDF5', file: 'h5' },
  { format: 'csv', label: 'CSV', file: 'csv' },
  { format: 'json', label: 'JSON', file: 'json' },
];

function why(run) {
  if (run.status === 'running') return 'the run is still recording: its samples can be exported when it ends';
  return null;
}

export function exportButtons(run) {
  const reason = why(run);
  const note = el('span', { class: 'note', id: 'export-note', role: 'status' }, reason ? `Exports: ${reason}.` : '');
  const buttons = EXPORT_FORMATS.map(({ format, label, file }) => {
    if (reason) {
      return el('button', { type: 'button', class: 'export', disabled: true, title: reason, 'data-format': format }, label);
    }
    const href = `/api/runs/${encodeURIComponent(run.id)}/export?format=${format}`;
    const name = `${run.unit_serial || 'run'}-${run.id}.${file}`;
    const link = el('a', { class: 'button export', href, download: name, 'data-format': format }, label);
    link.addEventListener('click', async (e) => {
      e.preventDefault();
      note.textContent = `Preparing ${label}…`;
      try {
        const { blob, samples } = await fetchFile(href);
        const url = URL.createObjectURL(blob);
        const a = el('a', { href: url, download: name });
        document.body.append(a);
        a.click();
        a.remove();
        setTimeout(() => URL.revokeObjectURL(url), 60000);
        note.textContent = `${label}: ${samples ? `${samples} samples, ` : ''}${Math.round(blob.size / 1024)} KiB saved.`;
      } catch (err) {
        note.textContent = `${label}: ${err.message || err}`;
      }
    });
    return link;
  });
  return el('div', { class: 'exports-bar no-print', id: 'exports-bar' },
    el('span', { class: 'label' }, 'Export samples:'), ...buttons, note);
}
