//! Which strands are drawn for a groom, where they grow and which guides
//! they follow: made once per style (and per edit), then rebuilt every
//! frame from the guides' strains ([`crate::hair::strain_blend`]).
//!
//! Per group:
//!
//! - Listed and scalp-grown roots (procedural groups): `render.count`
//!   strands (a group without a `render` section shares
//!   [`DEFAULT_DRAWN_STRANDS`] with the other such groups, by guide
//!   count), rooted on the group's part of the scalp, combed as its guides
//!   are (scalp groups), or scattered around the guides' roots with their
//!   nearest guide's frame (listed roots). Each blends the strains of its
//!   nearest guide (`Nearest`) or three nearest (`Blend3`, inverse squared
//!   distance), is shortened by up to `length_variation`, and gathers onto
//!   its nearest guide towards the tip by `clump` (curled groups without a
//!   `render` section: [`DEFAULT_CURL_CLUMP`]), as XGen's and Yeti's clump
//!   modifiers do: curls form ringlets around their guides.
//! - Imported strands: every strand of the groom, guides as simulated and
//!   the others (`guide: false`, `--guides K`) as their own imported shape
//!   bent by the strain change of their three nearest guides.
//!
//! The window draws fewer strands than a picture on a software adapter:
//! [`DrawnLayout::new`] scales every group's count down together to at
//! most `max_strands` (each group keeps at least one; imported guides are
//! always drawn).

use glam::{DVec3, Vec3};
use helixhair_physics::engine::Engine;
use helixhair_physics::{NaturalShape, RootPose};
use helixhair_render::interpolate::{Interpolation, guide_weights};
use helixhair_render::rng::SplitMix64;
use helixhair_render::scalp_sampling::poisson_disk_on_scalp;

use helixhair_render::strand_shape::{Clump, Shaping};

use crate::hair::colours::strand_colours;
use crate::hair::curl_variation::curl_variation;
use crate::hair::strain_blend::{DrawnStrand, blend_sources};
use crate::head::coil::CoilLeadIn;
use crate::head::groom::{Groom, placement_scalp, root_strains, scalp_root};
use crate::style::groom::{RenderStrands, StrandInterpolation};
use crate::style::imported::ImportedStrands;

/// Strands drawn for the groups that have no `render` section, shared
/// between them by guide count: as many as the window draws by default.
pub const DEFAULT_DRAWN_STRANDS: usize = 1000;

/// How far the drawn strands of a curled group without a `render`
/// section gather onto their guides at the tips: enough to read as
/// ringlets, with the roots still spread over the scalp.
pub const DEFAULT_CURL_CLUMP: f64 = 0.7;

/// Seed offset of the drawn strands' roots, so they do not coincide with
/// the guides' (which use the placement's own seed).
const RENDER_SEED: u64 = 0x5EED_F00D_DA7A;

/// Roots scattered around the guides' roots (for groups that list roots):
/// each near a random guide, within half the distance to that guide's
/// nearest neighbour.
fn scattered_roots(guide_roots: &[Vec3], count: usize, seed: u64) -> Vec<Vec3> {
    let mut rng = SplitMix64::new(seed);
    let spacing = |i: usize| {
        guide_roots
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != i)
            .map(|(_, q)| q.distance(guide_roots[i]))
            .fold(0.02f32, f32::min)
    };
    (0..count)
        .map(|_| {
            let i = rng.below(guide_roots.len());
            let offset = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) - 0.5;
            guide_roots[i] + offset * spacing(i)
        })
        .collect()
}

/// The drawn strands of a groom and their colours.
#[derive(Clone, Debug, Default)]
pub struct DrawnLayout {
    /// The strands, group by group.
    pub strands: Vec<DrawnStrand>,
    /// One colour per strand, linear RGB.
    pub colours: Vec<Vec3>,
    /// The guides (simulation indices) that strands clump onto or follow,
    /// each once, in order: the indices of [`Self::shapings`].
    pub shape_guides: Vec<usize>,
    /// How each strand is shaped by its guides after it is swept (its
    /// `clump` and `follow`, with its curl's own phase and radius), guides
    /// named by their place in [`Self::shape_guides`].
    pub shapings: Vec<Shaping>,
    /// Element count of every guide the layout was made for.
    guide_elements: Vec<usize>,
}

/// The guides of one group: indices in the simulation, roots, lengths.
struct Guides<'a> {
    index: Vec<usize>,
    roots: Vec<RootPose>,
    lengths_m: Vec<&'a [f64]>,
}

impl<'a> Guides<'a> {
    fn new(engine: &'a Engine, index: Vec<usize>) -> Self {
        Self {
            roots: index.iter().map(|&g| *engine.root(g)).collect(),
            lengths_m: index
                .iter()
                .map(|&g| engine.strand_model(g).lengths_m.as_slice())
                .collect(),
            index,
        }
    }

    fn root_points(&self) -> Vec<Vec3> {
        self.roots.iter().map(|r| r.position_m.as_vec3()).collect()
    }

    /// Weights (local guide, weight) of the guides a strand at `root`
    /// follows, the heaviest first.
    fn weights(&self, root: Vec3, method: Interpolation) -> Vec<(usize, f64)> {
        let mut w: Vec<(usize, f64)> = guide_weights(&self.root_points(), root, method)
            .into_iter()
            .map(|(g, w)| (g, f64::from(w)))
            .collect();
        w.sort_by(|a, b| b.1.total_cmp(&a.1));
        w
    }

    fn sources(
        &self,
        lengths_m: &[f64],
        weights: &[(usize, f64)],
    ) -> Vec<Vec<crate::hair::strain_blend::StrainSource>> {
        let guides: Vec<(usize, f64, &[f64])> = weights
            .iter()
            .map(|&(g, w)| (self.index[g], w, self.lengths_m[g]))
            .collect();
        blend_sources(lengths_m, &guides)
    }
}

impl DrawnLayout {
    /// The drawn strands of `groom`, whose grown style `engine` simulates,
    /// at most about `max_strands` of them.
    pub fn new(groom: &Groom, engine: &Engine, max_strands: usize) -> Self {
        let renders = group_renders(groom);
        let requested: usize = groom
            .groups()
            .zip(&renders)
            .map(|((_, grown), r)| {
                r.as_ref().map_or(0, |r| r.count as usize)
                    + grown.imported.as_ref().map_or(0, |i| i.strands.len())
            })
            .sum();
        let scale = (max_strands as f64 / requested.max(1) as f64).min(1.0);
        let mut layout = Self {
            guide_elements: (0..engine.strand_count())
                .map(|g| engine.strand_model(g).elements())
                .collect(),
            ..Self::default()
        };
        let mut first = 0;
        for (i, ((group, grown), render)) in groom.groups().zip(renders).enumerate() {
            let seed = i as u64 + 1;
            let listed = grown.roots.len();
            let end = (first + grown.simulated_count()).min(engine.strand_count());
            let root_guides = Guides::new(engine, (first..(first + listed).min(end)).collect());
            if let Some(render) = render.filter(|_| !root_guides.index.is_empty()) {
                let count = ((f64::from(render.count) * scale) as usize).max(1);
                let roots: Vec<RootPose> = match &group.scalp {
                    Some(placement) => {
                        let strains = root_strains(group);
                        let lead_in = CoilLeadIn::for_group(group);
                        poisson_disk_on_scalp(
                            &placement_scalp(placement, &groom.head),
                            count,
                            placement.seed ^ RENDER_SEED,
                        )
                        .iter()
                        .map(|s| scalp_root(s, placement, strains, lead_in.as_ref()).pose())
                        .collect()
                    }
                    None => {
                        let points = root_guides.root_points();
                        scattered_roots(&points, count, seed)
                            .into_iter()
                            .map(|p| {
                                let w = root_guides.weights(p, Interpolation::Nearest);
                                RootPose {
                                    position_m: p.as_dvec3(),
                                    head_from_root: root_guides.roots[w[0].0].head_from_root,
                                }
                            })
                            .collect()
                    }
                };
                let method = match render.method {
                    StrandInterpolation::Nearest => Interpolation::Nearest,
                    StrandInterpolation::Blend3 => Interpolation::Blend3,
                };
                let mut rng = SplitMix64::new(seed);
                let variation = render.length_variation.clamp(0.0, 0.9);
                for root in roots {
                    let weights = root_guides.weights(root.position_m.as_vec3(), method);
                    let shorter = 1.0 - variation * f64::from(rng.next_f32());
                    let lengths_m: Vec<f64> = root_guides.lengths_m[weights[0].0]
                        .iter()
                        .map(|l| l * shorter)
                        .collect();
                    let clump = (render.clump > 0.0)
                        .then(|| (root_guides.index[weights[0].0], render.clump));
                    // Hair that does not clump (straight and wavy) takes its
                    // shape from gravity and the head more than from its
                    // own curl: its tips follow the guides' blended shape.
                    let follow = if clump.is_some() {
                        Vec::new()
                    } else {
                        weights
                            .iter()
                            .map(|&(g, w)| (root_guides.index[g], w))
                            .collect()
                    };
                    layout.strands.push(DrawnStrand {
                        root,
                        base: vec![DVec3::ZERO; lengths_m.len()],
                        sources: root_guides.sources(&lengths_m, &weights),
                        lengths_m,
                        clump,
                        follow,
                    });
                }
                layout.colours.extend(strand_colours(
                    &render,
                    layout.strands.len() - layout.colours.len(),
                    seed,
                ));
            }
            if let Some(imported) = &grown.imported {
                let render = group.render.clone().unwrap_or_default();
                let guides = Guides::new(engine, ((first + listed)..end).collect());
                let before = layout.strands.len();
                layout.add_imported(imported, &guides, scale);
                let added = layout.strands.len() - before;
                layout.colours.extend(strand_colours(&render, added, seed));
            }
            first = end;
        }
        layout.shape_by_guides();
        layout
    }

    /// Fills [`Self::shape_guides`] and [`Self::shapings`] from the
    /// strands' clumps and follows.
    fn shape_by_guides(&mut self) {
        let mut slot_of = std::collections::BTreeMap::new();
        for strand in &self.strands {
            for g in strand
                .clump
                .iter()
                .map(|c| c.0)
                .chain(strand.follow.iter().map(|f| f.0))
            {
                slot_of.entry(g).or_insert(0);
            }
        }
        for (slot, value) in slot_of.values_mut().enumerate() {
            *value = slot;
        }
        self.shape_guides = slot_of.keys().copied().collect();
        self.shapings = self
            .strands
            .iter()
            .enumerate()
            .map(|(index, strand)| {
                let (phase_rad, curl_scale) = curl_variation(index);
                Shaping {
                    clump: strand.clump.map(|(g, amount)| Clump {
                        guide: slot_of[&g],
                        amount: amount as f32,
                        phase_rad,
                        curl_scale,
                    }),
                    follow: strand
                        .follow
                        .iter()
                        .map(|&(g, w)| (slot_of[&g], w as f32))
                        .collect(),
                }
            })
            .collect();
    }

    /// Whether `engine` still simulates the guides this layout was made
    /// for (same strands, same element counts).
    pub fn matches(&self, engine: &Engine) -> bool {
        self.guide_elements.len() == engine.strand_count()
            && self
                .guide_elements
                .iter()
                .enumerate()
                .all(|(g, &n)| engine.strand_model(g).elements() == n)
    }

    /// Every imported strand (`scale` of the non-guides, spread evenly):
    /// guides as simulated, the others their own strains plus the change
    /// of their nearest guides' strains from the guides' imported ones.
    fn add_imported(&mut self, imported: &ImportedStrands, guides: &Guides, scale: f64) {
        let rest: Vec<&[DVec3]> = imported.guides().map(|s| s.strains.as_slice()).collect();
        let mut next_guide = 0;
        let mut others = 0usize;
        for strand in &imported.strands {
            let lengths_m = vec![strand.element_length_m; strand.strains.len()];
            let root = strand.pose();
            let weights = if strand.guide {
                let own = next_guide;
                next_guide += 1;
                vec![(own, 1.0)]
            } else {
                others += 1;
                // Keep `scale` of the other strands, evenly.
                if ((others as f64) * scale).floor() == ((others - 1) as f64 * scale).floor() {
                    continue;
                }
                guides.weights(root.position_m.as_vec3(), Interpolation::Blend3)
            };
            if weights
                .iter()
                .any(|&(g, _)| g >= guides.index.len() || g >= rest.len())
            {
                continue;
            }
            let sources = guides.sources(&lengths_m, &weights);
            let base = sources
                .iter()
                .zip(&strand.strains)
                .map(|(sources, &own)| {
                    own - sources
                        .iter()
                        .zip(&weights)
                        .map(|(s, &(g, _))| {
                            s.weight * rest[g].get(s.element).copied().unwrap_or(DVec3::ZERO)
                        })
                        .sum::<DVec3>()
                })
                .collect();
            self.strands.push(DrawnStrand {
                root,
                lengths_m,
                base,
                sources,
                clump: None,
                follow: Vec::new(),
            });
        }
    }
}

/// Each group's `render` section, or the default one for a group without
/// (its share of [`DEFAULT_DRAWN_STRANDS`]), or `None` for a group with
/// no listed or grown roots.
fn group_renders(groom: &Groom) -> Vec<Option<RenderStrands>> {
    let unstyled: usize = groom
        .groups()
        .filter(|(g, _)| g.render.is_none())
        .map(|(_, grown)| grown.roots.len())
        .sum();
    // Shares by cumulative rounding, so they add up to the total exactly.
    let mut unstyled_before = 0;
    groom
        .groups()
        .map(|(group, grown)| {
            if grown.roots.is_empty() {
                return None;
            }
            Some(group.render.clone().unwrap_or_else(|| {
                let share_of = |guides: usize| DEFAULT_DRAWN_STRANDS * guides / unstyled.max(1);
                let share =
                    share_of(unstyled_before + grown.roots.len()) - share_of(unstyled_before);
                unstyled_before += grown.roots.len();
                let curled = matches!(group.params.natural_shape, NaturalShape::Helix { .. });
                RenderStrands {
                    count: share.max(grown.roots.len()) as u32,
                    length_variation: 0.15,
                    clump: if curled { DEFAULT_CURL_CLUMP } else { 0.0 },
                    ..RenderStrands::default()
                }
            }))
        })
        .collect()
}
