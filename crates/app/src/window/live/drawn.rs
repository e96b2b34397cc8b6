//! The window's drawn hair: the same strands `helixhair render` draws
//! ([`DrawnLayout`] and [`drawn_hair`]), so the window and the offline
//! pictures agree, for every style (a group without a `render` section
//! gets the default drawn strands in both).
//!
//! Drawing every strand a groom asks for (thousands) is too slow for a
//! software rasteriser, so the layout scales the counts down together to
//! at most the window's `--render-strands` (or the interactive preview's
//! count). The layout is made once per style, count and simulated guides,
//! and the strands are rebuilt from the guides' strains every frame.

use helixhair_physics::engine::Engine;
use helixhair_render::head_shell::HeadShell;
use helixhair_render::{HairStrands, HeadMesh};

use super::device_plan::DevicePlan;
use crate::hair::drawn::drawn_hair;
use crate::hair::layout::DrawnLayout;
use crate::head::groom::Groom;
use crate::style::Style;

/// The groom and layout of the style last drawn, rebuilt when the style,
/// the strand count or the simulated guides change.
#[derive(Debug, Default)]
pub struct DrawnCache {
    source: Option<(Style, usize)>,
    groom: Option<Groom>,
    layout: Option<DrawnLayout>,
    /// The layout's plan for drawing from the GPU engine's buffers, made
    /// with the layout (`None` inside: the layout cannot be).
    plan: Option<Option<DevicePlan>>,
}

impl DrawnCache {
    /// The drawn hair of `style` on `head` (head coordinates) from
    /// `engine`'s guides, in world coordinates, at most about
    /// `max_strands` strands; `None` when `engine` does not simulate the
    /// style's guides (an edit not yet simulated).
    pub fn strands(
        &mut self,
        style: &Style,
        head: &HeadMesh,
        engine: &Engine,
        max_strands: usize,
    ) -> Option<HairStrands> {
        if !self.prepare(style, head, engine, max_strands) {
            return None;
        }
        Some(drawn_hair(
            self.groom.as_ref()?,
            self.layout.as_ref()?,
            engine,
        ))
    }

    /// Makes the groom and layout of [`Self::strands`] for these arguments
    /// if they are not made yet; whether `engine` simulates the style's
    /// guides (else nothing can be drawn from it yet).
    pub fn prepare(
        &mut self,
        style: &Style,
        head: &HeadMesh,
        engine: &Engine,
        max_strands: usize,
    ) -> bool {
        // Compared in place: a groom's style is megabytes, cloned only on
        // a change.
        let same = self
            .source
            .as_ref()
            .is_some_and(|(s, m)| s == style && *m == max_strands);
        if !same {
            self.groom = Some(Groom::new(style.clone(), head.clone()));
            self.layout = None;
            self.source = Some((style.clone(), max_strands));
        }
        let Some(groom) = self.groom.as_ref() else {
            return false;
        };
        if groom.grown.strand_count() != engine.strand_count() {
            return false;
        }
        if !self.layout.as_ref().is_some_and(|l| l.matches(engine)) {
            self.layout = Some(DrawnLayout::new(groom, engine, max_strands));
            self.plan = None;
        }
        true
    }

    /// The plan for drawing the layout [`Self::prepare`] last made from
    /// `engine`'s own GPU buffers ([`DevicePlan`]), with the groom's shell,
    /// where the layout allows it: made once per layout.
    pub fn device_plan(&mut self, engine: &Engine) -> Option<(&DevicePlan, &HeadShell)> {
        let groom = self.groom.as_ref()?;
        let layout = self.layout.as_ref().filter(|l| l.matches(engine))?;
        let plan = self
            .plan
            .get_or_insert_with(|| DevicePlan::new(layout, engine))
            .as_ref()?;
        Some((plan, &groom.shell))
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use helixhair_render::head_generate::default_head;

    use super::*;
    use crate::hair::drawn::drawn_hair_full;
    use crate::hair::layout::DEFAULT_DRAWN_STRANDS;
    use crate::sim::build::SimOverrides;
    use crate::sim::grown::grown_sim;

    /// The window drew a fringe over the face for styles without `render`
    /// sections while `render` drew their guides only: both now draw the
    /// same strands, point for point.
    #[test]
    fn the_window_draws_what_render_draws() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../assets/styles/straight.ron"
        );
        let (groom, mut sim) =
            grown_sim(Path::new(path), None, SimOverrides::default()).expect("grows");
        sim.run(5).expect("finite");
        let pictured = drawn_hair_full(&groom, sim.engine());
        let mut cache = DrawnCache::default();
        let windowed = cache
            .strands(&groom.style, &default_head(), sim.engine(), usize::MAX)
            .expect("guides match");
        assert_eq!(pictured.strands, windowed.strands);
        assert_eq!(pictured.colours, windowed.colours);
        // Not only the guides: the default drawn strands.
        let guides = sim.engine().strand_count();
        assert!(
            pictured.strands.strand_count() >= DEFAULT_DRAWN_STRANDS.max(guides),
            "{} strands for {guides} guides",
            pictured.strands.strand_count()
        );
        // The window's cap scales the counts down.
        let capped = cache
            .strands(&groom.style, &default_head(), sim.engine(), 300)
            .expect("guides match");
        let n = capped.strands.strand_count();
        assert!((300 - 5..=300 + 5).contains(&n), "{n}");
    }
}
