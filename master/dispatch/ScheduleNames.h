// The names of the tile schedules: one table for the command line (--schedule, --schedules), the
// run summary and the speedup report, as scene/SettingNames.h is for the scene's settings.
#pragma once

#include "cluster/DistributionOptions.h"
#include "scene/SettingNames.h"

namespace prism {

inline constexpr NamedValue<Schedule> kScheduleList[] = {{"dynamic", Schedule::Dynamic},
                                                         {"static", Schedule::Static}};
inline constexpr NameTable<Schedule> kScheduleNames{kScheduleList};

}  // namespace prism
