#pragma once
// The panels of `diagnose --plot`: the record's Allan deviation with the baseline and the verdict
// model (each with its 95 % band), the points where the record leaves the baseline marked on
// top, and one panel per other view that departs, as standardised residuals z of the record
// against the baseline and against the verdict model with the gap level +-threshold drawn.
#include <string>
#include <vector>

#include "app/reports/allan_plot.h"
#include "app/reports/diagnose_units.h"
#include "experiments/diagnosis/diagnose.h"

namespace allanlab::app {

// The Allan deviation in the report's unit of the column's sensor (app/reports/diagnose_units.h).
std::vector<AllanPlot> DiagnosePanels(const experiments::DiagnosisSummary& s, const std::string& title,
                                      const DiagnoseUnits& units);

}  // namespace allanlab::app
