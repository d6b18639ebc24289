#pragma once
// The report's section on the twin as a diagnostic (results.json twin.diagnosis): each flag with
// the order it sits on and the sources the twin's model ranks there, or that none was raised.

#include "wavebench/report/html_page.hpp"
#include "wavebench/report/run_folder.hpp"

namespace wavebench::report {

// Adds nothing when the run has no twin diagnosis.
void add_twin_diagnosis_section(HtmlPage& page, const RunFolder& run);

}  // namespace wavebench::report
