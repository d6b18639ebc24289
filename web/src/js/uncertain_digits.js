// A figure with its expanded uncertainty U, to the digits U supports: U to two significant
// digits, the value rounded at the same decimal (GUM 7.2.6). "5.7034 ± 0.0213" reads
// "5.703 ± 0.021"; "612.4 ± 23.7" reads "612 ± 24"; "1234 ± 230" reads "1230 ± 230".
export function roundedToUncertainty(value, expanded) {
  const v = Number(value);
  const u = Number(expanded);
  if (value == null || !Number.isFinite(v) || !(u > 0) || !Number.isFinite(u)) return null;
  const last = Math.floor(Math.log10(u)) - 1;  // the decimal exponent of U's second digit
  const text = (x) => {
    if (last < 0) {
      const fixed = x.toFixed(-last);
      return /^-0\.?0*$/.test(fixed) ? fixed.slice(1) : fixed;
    }
    const step = 10 ** last;
    const r = Math.round(x / step) * step;
    return String(r === 0 ? 0 : r);
  };
  return { value: text(v), expanded: text(u) };
}
