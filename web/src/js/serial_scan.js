// A barcode scanner is a keyboard: it types the serial and presses Enter. Nothing here starts a
// run. Enter in the serial field moves the focus to Start (a deliberate click, or a second key
// on Start, starts); a new burst of characters replaces a finished serial, wherever the focus
// was when it began (on Start after the last scan, say); and the Enter that ended a scan, or
// a scanner's trailing CR/LF, never counts as a key on Start.
const GUARD_MS = 600;  // a scanner's suffix (CR LF) and key repeat arrive well within this

function editable(node) {
  if (!node) return false;
  if (node.isContentEditable) return true;
  if (node.tagName === 'TEXTAREA' || node.tagName === 'SELECT') return true;
  if (node.tagName !== 'INPUT') return false;
  return !['button', 'submit', 'reset', 'checkbox', 'radio', 'range', 'color', 'file']
    .includes(node.type);
}

// A key that types a serial's character: serials are [A-Za-z0-9._/-], never a space (Space is
// the explicit key on a focused Start).
function serialCharacter(e) {
  return e.key.length === 1 && e.key !== ' ' && !e.ctrlKey && !e.metaKey && !e.altKey;
}

export class SerialScan {
  constructor({ field, start, onScanned }) {
    this.field = field;
    this.start = start;
    this.onScanned = onScanned || (() => {});
    this.finished = false;  // the field holds a serial ended by Enter: the next burst replaces it
    this.scanEndedAt = -Infinity;

    // Focus selects the whole serial, so what is typed or scanned next replaces it.
    field.addEventListener('focus', () => {
      if (this.typingInto) return;
      field.select();
      this.selectedOnFocus = true;
    });
    // The mouseup of the click that focused the field would put a caret in the selection.
    field.addEventListener('mouseup', (e) => {
      if (this.selectedOnFocus) e.preventDefault();
      this.selectedOnFocus = false;
    });
    field.addEventListener('blur', () => { this.selectedOnFocus = false; });
    field.addEventListener('keydown', (e) => {
      if (e.key === 'Enter') {
        e.preventDefault();
        this.finish();
      } else if (serialCharacter(e) && this.finished) {
        field.value = '';
        this.finished = false;
      }
    });
    field.addEventListener('input', () => { this.finished = false; });
    // A burst that starts where nothing takes text (Start, the page) goes to the serial field.
    document.addEventListener('keydown', (e) => {
      if (!serialCharacter(e) || editable(document.activeElement)) return;
      if (document.querySelector('dialog[open]')) return;
      e.preventDefault();
      this.typingInto = true;
      field.focus();
      this.typingInto = false;
      field.value = e.key;
      field.setSelectionRange(field.value.length, field.value.length);
      this.finished = false;
      field.dispatchEvent(new Event('input', { bubbles: true }));
    }, true);
    start.addEventListener('keydown', (e) => {
      if ((e.key === 'Enter' || e.key === ' ') && this.justScanned()) e.preventDefault();
    });
  }

  finish() {
    this.finished = true;
    this.scanEndedAt = performance.now();
    if (!this.start.disabled) this.start.focus();
    this.onScanned(this.field.value.trim());
  }

  // Whether a key activation of Start is the tail of a scan rather than the operator's.
  justScanned() {
    return performance.now() - this.scanEndedAt < GUARD_MS;
  }

  // After a start: the serial stays shown, and the next scan replaces it.
  markFinished() {
    this.finished = true;
  }
}
