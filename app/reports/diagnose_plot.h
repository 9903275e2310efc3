#pragma once
// The panels of `diagnose --plot`: the record's Allan deviation with the baseline (its 95 % band
// as an outline) and the verdict model (its 95 % band filled), the points where the record leaves
// the baseline marked on top and the tau ranges where any view departs as a light strip along
// the tau axis; one panel per other departing tau view, as standardised residuals z of the record
// against the baseline and the verdict model with the gap level +-threshold; and for a departing
// block-mean view (change_point, trend) the record's block means over time with the baseline's
// level and the verdict model's path, the located step or settling marked along the time axis.
// Keys sit under the axes, never over a curve.
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
