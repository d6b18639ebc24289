#pragma once
// A procedure run `repeats` times in one run (issue #11, bench.md §4): the results sections of
// the repeats combined into one, generically, so that any procedure whose figures are
// UncertainFigure objects (to_json) gets it without code of its own.
//
// The first repeat's sections are the skeleton (points, traces, spectra, counts stay the first
// repeat's; every repeat's own sections are kept in results.json `repeats`). Every uncertain
// figure in it, found wherever it sits (an object in the to_json shape, also inside an
// `uncertainty` object and its arrays), is replaced by the mean over the repeats, with:
//   - the contributions that differ from one repeat to the next (varies_between_repeats: the
//     noise after window averaging, the settle criterion, the dynamic record's sample noise,
//     the lost-motion fit's misfit) taken out, because the spread between repeats contains
//     them;
//   - the others kept, RMS over the repeats: the encoders' quantisation at the same counts, and
//     the selection of extremes (the mean of upward-biased p2p values is as biased);
//   - "spread between repeats" (type A) added: s/√R over the R values, but not below the RMS
//     of the removed contributions over √R, so that two or three repeats that happen to agree
//     do not claim less than what each one showed of its own noise.
// A plain number beside an `uncertainty` object, under the same key as one of its figures,
// becomes that figure's mean too, so the reported figure and its uncertainty stay together.

#include <nlohmann/json.hpp>
#include <vector>

namespace wavebench::procedures {

inline constexpr const char* kRepeatSpreadSource = "spread between repeats";

// `repeats` holds one object of sections per repeat (at least one), all of the same procedure.
nlohmann::json combine_repeats(const std::vector<nlohmann::json>& repeats);

}  // namespace wavebench::procedures
