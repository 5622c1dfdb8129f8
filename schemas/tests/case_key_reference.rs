//! Tests of `schemas::case::key_reference`.

use schemas::case::key_reference::*;

#[test]
fn units_ranges_and_used_by_come_out_of_the_doc_comment() {
    assert_eq!(unit("Sound speed c [m/s]; default u_max / 0.2"), "m/s");
    assert_eq!(unit("`[x, y]` of the probe [m]"), "m");
    assert_eq!(unit("`[x, y]` of the probe"), "");
    assert_eq!(
        split_used_by("E-MPS only: α of Monaghan's viscosity."),
        Some(("E-MPS".into(), "α of Monaghan's viscosity.".into()))
    );
    assert_eq!(
        split_used_by("ISPH only: the ISPH settings."),
        Some(("ISPH".into(), "The ISPH settings.".into()))
    );
    assert_eq!(split_used_by("Only with `method = \"isph\"`: x"), None);
    assert_eq!(
        split_range("Density [kg/m³]. Range: > 0."),
        ("> 0".into(), "Density [kg/m³].".into())
    );
    assert_eq!(
        split_range("α. Range: [1.5, wall_layers − 0.5]. Then more."),
        ("[1.5, wall_layers − 0.5]".into(), "α. Then more.".into())
    );
    assert_eq!(
        plain_links("see [`FluidConfig::gpu_support`] and [a](b)"),
        "see `FluidConfig::gpu_support` and [a](b)"
    );
}
