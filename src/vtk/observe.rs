//! The frames of a run written by an observer ([`crate::observe`]).

use std::path::PathBuf;

use super::dem::dem_frame;
use super::series::PvdSeries;
use crate::error::Result;
use crate::explicit::ExplicitDynamics;
use crate::integrate::ExplicitIntegrator;
use crate::law::ContactLaw;
use crate::observe::{Event, Observer};

/// An observer of the explicit driver that writes a [`dem_frame`] into a
/// [`PvdSeries`] at each step it is called for (wrap it in
/// [`crate::observe::every`] to write every n-th step) and at the end of
/// the run (unless the last step was just written). The state before the
/// first step is not an event: write it with [`DemFrames::write`] before
/// the run if the series should start there.
#[derive(Debug)]
pub struct DemFrames {
    series: PvdSeries,
    segments: usize,
}

impl DemFrames {
    /// Frames into `folder` (see [`PvdSeries::new`]), circles and ellipses
    /// drawn with `segments` sides.
    ///
    /// # Errors
    /// As [`PvdSeries::new`].
    pub fn new(folder: impl Into<PathBuf>, segments: usize) -> Result<Self> {
        Ok(Self {
            series: PvdSeries::new(folder)?,
            segments,
        })
    }

    /// The series written so far.
    pub fn series(&self) -> &PvdSeries {
        &self.series
    }

    /// Write the frame of `dem` as it is now (e.g. its initial state,
    /// before a run), at its time.
    ///
    /// # Errors
    /// Those of [`dem_frame`] and [`PvdSeries::write_frame`].
    pub fn write<L: ContactLaw<2>, I: ExplicitIntegrator>(
        &mut self,
        dem: &ExplicitDynamics<L, I>,
    ) -> Result<()> {
        self.series
            .write_frame(dem.time(), &dem_frame(dem, self.segments)?)
    }
}

impl<L: ContactLaw<2>, I: ExplicitIntegrator> Observer<ExplicitDynamics<L, I>> for DemFrames {
    fn observe(&mut self, dem: &ExplicitDynamics<L, I>, event: &Event<'_>) -> Result<()> {
        let time = match *event {
            Event::Step { time, .. } | Event::Finished { time, .. } => time,
            Event::Check { .. }
            | Event::SubStep { .. }
            | Event::Halved { .. }
            | Event::Iteration { .. }
            | Event::Trial { .. } => return Ok(()),
        };
        if self.series.last_time() == Some(time) {
            return Ok(());
        }
        self.write(dem)
    }
}
