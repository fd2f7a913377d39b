//! Writing the report's files.

use super::format::slug;
use super::plot::{deviation_svg, time_svg};
use super::results::{LimitSurface, Report};
use super::tessellated::Tessellated;
use std::path::Path;
use subdiv::io::atomic::write_bytes as write_atomically;
use subdiv::{Error, Result};

impl Report {
    /// Writes `dir/report.md`, `dir/report.html` and `dir/figures/*.svg`
    /// (creating the directories), each file atomically.
    pub fn write(&self, dir: &Path) -> Result<()> {
        let figures = dir.join("figures");
        std::fs::create_dir_all(&figures).map_err(|source| Error::Io {
            path: figures.clone(),
            source,
        })?;
        for (idx, i) in self.inputs.iter().enumerate() {
            let sl = slug(idx, &i.name);
            write_atomically(
                &figures.join(format!("{sl}-deviation.svg")),
                deviation_svg(i, &self.settings).as_bytes(),
            )?;
            write_atomically(
                &figures.join(format!("{sl}-time.svg")),
                time_svg(i).as_bytes(),
            )?;
            write_atomically(
                &figures.join(format!("{sl}-shape.svg")),
                i.picture.svg.as_bytes(),
            )?;
            if let LimitSurface::Compared { picture, .. } = &i.limit_surface {
                write_atomically(&figures.join(format!("{sl}-limit.svg")), picture.as_bytes())?;
            }
            if let Tessellated::Compared { picture, .. } = &i.tessellated {
                write_atomically(
                    &figures.join(format!("{sl}-tessellated.svg")),
                    picture.as_bytes(),
                )?;
            }
        }
        write_atomically(&dir.join("report.md"), self.markdown().as_bytes())?;
        write_atomically(&dir.join("report.html"), self.html().as_bytes())?;
        Ok(())
    }
}
