#pragma once
// `coif db plot`: a picture of one record, for people to look at. One panel per view azimuth
// (θv = 0°, 45°, 135°, 180°, top to bottom); in each, against position x ∈ [0, W) left to right:
//   white  α(x)
//   red    re(x) at θl = θv (light behind the eye)
//   green  re(x) at θl = θv + 90°
//   blue   re(x) at θl = 0 (light from outside, along the outward radial direction)
// The vertical axis runs from 0 (panel bottom, grey line) to 1 (panel top, grey line); no text.
#include "db/hrir_db.h"
#include "models/core/image.h"

namespace coif {

inline constexpr int kPlotPanelWidth = 640, kPlotPanelHeight = 160;
Image plot_record(const HrirDatabase& db, std::size_t record);

}  // namespace coif
