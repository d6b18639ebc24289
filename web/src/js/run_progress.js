// Progress as the daemon states it (issue #21): the recording's time left, and the post-run
// work (twin, calibration, results, unit twin, report) of recorded runs going on in the
// background while the bench takes the next unit. The daemon estimates the time left; the
// page shows it as given.

export function timeLeft(seconds) {
  if (seconds === null || seconds === undefined || seconds < 0) return '';
  if (seconds < 1.5) return 'about a second left';
  if (seconds < 90) return `about ${Math.ceil(seconds)} s left`;
  return `about ${Math.ceil(seconds / 60)} min left`;
}

// One line per run whose results are still being made, into `box` (hidden when none).
export function showPostRuns(box, postRuns) {
  const list = postRuns || [];
  box.hidden = !list.length;
  box.replaceChildren(...list.map((p) => {
    const row = document.createElement('div');
    row.className = 'post-run';
    const link = document.createElement('a');
    link.href = `/run?id=${encodeURIComponent(p.run_id)}`;
    link.textContent = `${p.serial || ''} ${p.procedure} ${p.run_id}`.trim();
    const bar = document.createElement('progress');
    bar.max = 1;
    bar.value = p.progress || 0;
    row.append('Results being made: ', link,
      ` · ${p.phase} · ${Math.round(100 * (p.progress || 0))} % · ${timeLeft(p.remaining_s)} `, bar);
    return row;
  }));
}

// On the run page of a recorded run whose results are still being made: where that work is,
// re-read every 2 s (`read` returns GET /api/runs/{id}) until the run is finished, then
// `done()` (the page shows the results).
export function awaitResults(detail, box, read, done) {
  const show = (d) => {
    const p = d.post_run;
    box.hidden = false;
    box.className = 'message';
    box.textContent = p
      ? `Recorded; results being made: ${p.phase} · ${Math.round(100 * (p.progress || 0))} % · ${timeLeft(p.remaining_s)}`
      : 'Recording…';
  };
  show(detail);
  const tick = async () => {
    try {
      const d = await read();
      if (d.run.status !== 'running') {
        box.hidden = true;
        done();
        return;
      }
      show(d);
    } catch (_) {
      // A missed read is retried at the next tick.
    }
    setTimeout(tick, 2000);
  };
  setTimeout(tick, 2000);
}
