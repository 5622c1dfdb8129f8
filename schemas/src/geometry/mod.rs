//! Geometry read from files and turned into lattice sites: triangle meshes from STL and OBJ files
//! ([`read_mesh`], [`TriangleMesh`] with its solid checks and mass properties), terrains from ESRI
//! ASCII grids ([`read_height_grid`], [`HeightGrid`]), and the sites of a simple cubic
//! [`Lattice`] inside a mesh or below a terrain ([`sites_inside_mesh`], [`sites_below_surface`])
//! as a [`SiteSet`], with the skin of such a set ([`SiteSet::within_layers_of_outside`]): what
//! wall particles are built from.

pub mod ascii_grid;
pub mod error;
pub mod geotiff;
pub mod height_grid;
pub mod lattice;
pub mod lattice_fill;
pub mod mass_properties;
pub mod mesh_checks;
pub mod mesh_file;
pub mod site_set;
pub mod triangle_mesh;
pub mod vec3;

pub use ascii_grid::{read_height_grid, write_ascii_grid};
pub use error::{EdgeFault, GridError, MeshError, MeshProblem};
pub use geotiff::{read_geotiff, write_geotiff};
pub use height_grid::HeightGrid;
pub use lattice::Lattice;
pub use lattice_fill::{sites_below_surface, sites_inside_mesh};
pub use mass_properties::MassProperties;
pub use mesh_file::{read_mesh, write_binary_stl, MESH_EXTENSIONS};
pub use site_set::SiteSet;
pub use triangle_mesh::{rotation_matrix, TriangleMesh};
