//! Every finding's id, the name a report, the class report and the lessons know it by. The
//! findings name each other through these (a misspelt one does not compile).

pub const NAN_BLOCKER_DEPTH: &str = "nan_blocker_depth";
pub const NAN_VISIBILITY: &str = "nan_visibility";
pub const VISIBILITY_OUT_OF_RANGE: &str = "visibility_out_of_range";
pub const VISIBILITY_SCALED: &str = "visibility_scaled";
pub const LIGHT_MODEL_MATRIX: &str = "light_model_matrix";
pub const LIGHT_DIRECTION_OFF: &str = "light_direction_off";
pub const LIGHT_FRUSTUM_CLIPS: &str = "light_frustum_clips";
pub const LIGHT_NOT_DRAWN: &str = "light_not_drawn";
pub const LIGHT_MATRIX_STALE: &str = "light_matrix_stale";
pub const SHADOWS_MISSING: &str = "shadows_missing";
pub const PETER_PANNING: &str = "peter_panning";
pub const UMBRA_NOT_DARK: &str = "umbra_not_dark";
pub const DEPTH_ROUND_TRIP_WRONG: &str = "depth_round_trip_wrong";
pub const SEARCH_RADIUS_WRONG: &str = "search_radius_wrong";
pub const FILTER_RADIUS_NOT_FINITE: &str = "filter_radius_not_finite";
pub const RECEIVER_COUNTS_AS_BLOCKER: &str = "receiver_counts_as_blocker";
pub const BLOCKER_DEPTH_WRONG: &str = "blocker_depth_wrong";
pub const PENUMBRA_ESTIMATE_WRONG: &str = "penumbra_estimate_wrong";
pub const SAMPLES_NOT_AROUND_RECEIVER: &str = "samples_not_around_receiver";
pub const PENUMBRA_LAW_WRONG: &str = "penumbra_law_wrong";
pub const FILTER_IGNORES_BLOCKER: &str = "filter_ignores_blocker";
pub const SEARCH_AND_FILTER_LIGHTS_DIFFER: &str = "search_and_filter_lights_differ";
pub const SELF_SHADOWING: &str = "self_shadowing";
pub const ROUND_TRIP_ACNE: &str = "round_trip_acne";
pub const NO_PENUMBRA: &str = "no_penumbra";
pub const NO_CONTACT_HARDENING: &str = "no_contact_hardening";
pub const DEPENDS_ON_UNCLEARED_MAP: &str = "depends_on_uncleared_map";
