//! VTK unstructured-grid output of a frame: one line cell per element, with hinge and fracture flags
//! and section forces.

use super::Frame;
use std::fmt::Write as _;
use std::path::Path;

impl Frame {
    /// Writes the frame as an ASCII `.vtu`: points = nodes (with velocity and angular velocity),
    /// cells = elements (with member, hinge: 0 none / 1 at the first node / 2 at the second, the
    /// number of fractures, and the section forces N, Vy, Vz, T and the moments My, Mz at the
    /// element's first and second node, `section_forces.rs`).
    pub fn write_vtu(&self, path: &Path) -> std::io::Result<()> {
        let mut s = String::new();
        let (np, nc) = (self.nodes.len(), self.elements.len());
        let _ = writeln!(s, "<?xml version=\"1.0\"?>");
        let _ = writeln!(
            s,
            "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">"
        );
        let _ = writeln!(
            s,
            "<UnstructuredGrid><Piece NumberOfPoints=\"{np}\" NumberOfCells=\"{nc}\">"
        );
        s.push_str("<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
        for n in &self.nodes {
            let _ = writeln!(s, "{} {} {}", n.position.x, n.position.y, n.position.z);
        }
        s.push_str("</DataArray></Points>\n<PointData>\n");
        for (name, range) in [("velocity", 0..3), ("angular_velocity", 3..6)] {
            let _ = writeln!(
                s,
                "<DataArray type=\"Float64\" Name=\"{name}\" NumberOfComponents=\"3\" format=\"ascii\">"
            );
            for n in &self.nodes {
                let v = &n.velocity[range.clone()];
                let _ = writeln!(s, "{} {} {}", v[0], v[1], v[2]);
            }
            s.push_str("</DataArray>\n");
        }
        s.push_str(
            "</PointData>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n",
        );
        for e in &self.elements {
            let _ = writeln!(s, "{} {}", e.nodes[0], e.nodes[1]);
        }
        s.push_str("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
        for i in 0..nc {
            let _ = writeln!(s, "{}", 2 * (i + 1));
        }
        s.push_str("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
        for _ in 0..nc {
            s.push_str("3\n");
        }
        s.push_str("</DataArray>\n</Cells>\n<CellData>\n");
        let member: Vec<i64> = self.elements.iter().map(|e| e.member as i64).collect();
        let hinge: Vec<i64> = self
            .stresses
            .current()
            .iter()
            .map(|s| s.hinge.map_or(0, |end| end.node() as i64 + 1))
            .collect();
        let fractures: Vec<i64> = self.elements.iter().map(|e| i64::from(e.fractures)).collect();
        for (name, values) in [("member", member), ("hinge", hinge), ("fractures", fractures)] {
            let _ = writeln!(s, "<DataArray type=\"Int64\" Name=\"{name}\" format=\"ascii\">");
            for v in values {
                let _ = writeln!(s, "{v}");
            }
            s.push_str("</DataArray>\n");
        }
        let forces = self.section_forces();
        let columns: [(&str, usize, usize); 8] = [
            ("N", 0, 0),
            ("Vy", 0, 1),
            ("Vz", 0, 2),
            ("T", 0, 3),
            ("My_start", 0, 4),
            ("My_end", 1, 4),
            ("Mz_start", 0, 5),
            ("Mz_end", 1, 5),
        ];
        for (name, end, k) in columns {
            let _ = writeln!(s, "<DataArray type=\"Float64\" Name=\"{name}\" format=\"ascii\">");
            for f in &forces {
                let _ = writeln!(s, "{}", f[end][k]);
            }
            s.push_str("</DataArray>\n");
        }
        s.push_str("</CellData>\n</Piece></UnstructuredGrid>\n</VTKFile>\n");
        schemas::atomic_file::write(path, s)
    }
}
