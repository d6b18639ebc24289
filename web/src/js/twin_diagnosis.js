// The twin as a diagnostic (results.json twin.diagnosis, /api/status run.diagnosis_flags):
// each flag with the order it sits on and what the twin's model ranks first there.
import { el, num, table, section } from './dom.js';

function rankedFirst(flag) {
  const s = (flag.sources || [])[0];
  if (!s) return 'none of the model\u2019s lines';
  return `${s.source} [${s.family}]${s.harmonic > 1 ? `, harmonic ${s.harmonic}` : ''}`;
}

// A table of flags (the live console and the run page show the same columns).
export function diagnosisFlagsTable(flags, id) {
  return table([
    { label: 'Order', value: (f) => String(f.order), class: 'n' },
    { label: 'Residual [arcsec]', value: (f) => num(f.amplitude_arcsec), class: 'n' },
    { label: 'Band [arcsec]', value: (f) => num(f.band_arcsec), class: 'n' },
    { label: 'First revolution', value: (f) => String(f.first_revolution), class: 'n' },
    { label: 'Flagged at [s]', value: (f) => num(f.flagged_s), class: 'n' },
    { label: 'Ranked first by the twin', value: rankedFirst },
    { label: 'Suspect', value: (f) => el('span', { class: 'fail' }, f.suspect || '') },
  ], flags, { id });
}

export function twinDiagnosisSection(results) {
  const d = results.twin && results.twin.diagnosis;
  if (!d) return [];
  const flags = d.flags || [];
  const revolutions = (d.revolutions || []).length;
  const band = d.band || {};
  const note = el('p', { class: 'note' },
    `The residual of each whole output revolution against its band (the sensor floor, ` +
    `${num(band.noise_factor)}\u00d7 the median line, ${num(100 * (band.relative_band || 0))} % of the twin\u2019s own line); ` +
    `${revolutions} revolutions analysed.`);
  if (!flags.length) {
    return [section('twin-diagnosis', 'Twin diagnosis', note,
      el('p', { id: 'diagnosis-none' }, revolutions ? 'No flag: no line of the residual left its band.' : 'No whole output revolution to watch.'))];
  }
  return [section('twin-diagnosis', 'Twin diagnosis', note, diagnosisFlagsTable(flags, 'diagnosis-table'))];
}
