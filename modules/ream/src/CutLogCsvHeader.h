#pragma once
// The cut log CSV's header line (without its line break): written by cutLogCsv, required by cutLogFromCsv.
namespace reamsim::detail {

inline constexpr const char* kCutLogCsvHeader =
    "step,time_utc,tip_x,tip_y,tip_z,axis_x,axis_y,axis_z,boxes_overlap,contact,min_distance_mm,removed_mm3,"
    "cumulative_mm3,cut_ms,faces,contact_x,contact_y,contact_z,bone_state,move_contact_t,move_contact_x,"
    "move_contact_y,move_contact_z,reamer,reamer_diameter_mm,reamer_sphere_radius_mm";

}  // namespace reamsim::detail
