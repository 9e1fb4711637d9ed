#pragma once
// The cut log CSV's header line (without its line break): written by cutLogCsv, required by cutLogFromCsv.
namespace reamsim::detail {

#define REAMSIM_CUT_LOG_COLUMNS                                                                                   \
  "step,time_utc,tip_x,tip_y,tip_z,axis_x,axis_y,axis_z,boxes_overlap,contact,min_distance_mm,removed_mm3,"      \
  "cumulative_mm3,cut_ms,faces,contact_x,contact_y,contact_z,bone_state,move_contact_t,move_contact_x,"          \
  "move_contact_y,move_contact_z,reamer,reamer_diameter_mm,reamer_sphere_radius_mm"
inline constexpr const char* kCutLogCsvHeader = REAMSIM_CUT_LOG_COLUMNS ",undone,note";
// The same with each row's version and inclination in a scapular frame (cutLogCsv with a frame: an export for
// review; the angles follow from the axis and the landmarks, so reading takes them as checked numbers only).
inline constexpr const char* kCutLogCsvHeaderWithAngles = REAMSIM_CUT_LOG_COLUMNS ",undone,note,version_deg,inclination_deg";
// Headers written before, still read: without `undone` (session 55: every row read as not undone), and without
// notes either (before session 55: every note empty).
inline constexpr const char* kCutLogCsvHeaderWithoutUndone = REAMSIM_CUT_LOG_COLUMNS ",note";
inline constexpr const char* kCutLogCsvHeaderWithoutNotes = REAMSIM_CUT_LOG_COLUMNS;
#undef REAMSIM_CUT_LOG_COLUMNS

}  // namespace reamsim::detail
