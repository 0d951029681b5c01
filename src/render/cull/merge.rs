//! Step 4 of `render::cull`: a second render merged into the first pixel by pixel, and the
//! re-decided pixels of the merged frame.

use super::{Second, Trial, inside};
use crate::kernel::closer;
use crate::par::prelude::*;
use crate::render::Frame;

/// Merges `g`, the second render `second` of the clusters `failed` (re-decided pixels
/// `g_redone`), into `f` (re-decided pixels `f_redone`) (module comment, step 4). Where `G`
/// re-decided a pixel that a failed cluster may reach nearer than `F`'s hit, neither frame
/// holds the pixel's value: those pixels come back as the error, and `f` is left as it was.
pub(crate) fn merge(
    f: &mut Frame<f32>,
    f_redone: &[usize],
    (g, g_redone): (&Frame<f32>, &[usize]),
    second: &Second,
    failed: &[Trial],
    known: &[Pixel],
) -> Result<(), Vec<usize>> {
    let width = f.width as usize;
    // the pixels decided one by one, and their values
    let mut fixed: Vec<Pixel> = Vec::new();
    let mut unsettled = Vec::new();
    let at = |fr: &Frame<f32>, p: usize| (fr.ids[p], fr.depth[p]);
    for &p in &second.complete {
        fixed.push((p, at(g, p)));
    }
    let is_known = |p: usize| known.iter().any(|&(q, _)| q == p);
    for &p in g_redone {
        if second.complete.contains(&p) || is_known(p) {
            continue;
        }
        // where no failed cluster reaches, or `F`'s hit is nearer than any of theirs, `F`
        let nearest = (failed.iter())
            .filter(|&&(_, rect, _)| inside(p, width, rect))
            .map(|&(.., near)| near)
            .fold(f32::INFINITY, f32::min);
        if nearest == f32::INFINITY || !f_redone.contains(&p) && f.depth[p] < nearest {
            fixed.push((p, at(f, p)));
        } else {
            unsettled.push(p);
        }
    }
    if !unsettled.is_empty() {
        return Err(unsettled);
    }
    for &p in f_redone {
        if !second.complete.contains(&p) {
            fixed.push((p, at(f, p)));
        }
    }
    (f.ids
        .par_chunks_mut(width)
        .zip(f.depth.par_chunks_mut(width)))
    .zip(g.ids.par_chunks(width).zip(g.depth.par_chunks(width)))
    .for_each(|((fi, fd), (gi, gd))| {
        for x in 0..fi.len() {
            if closer(gd[x], gi[x], fd[x], fi[x]) {
                (fi[x], fd[x]) = (gi[x], gd[x]);
            }
        }
    });
    for (p, (id, t)) in fixed.into_iter().chain(known.iter().copied()) {
        (f.ids[p], f.depth[p]) = (id, t);
    }
    Ok(())
}

/// A pixel (row-major index) and its id and depth.
pub(crate) type Pixel = (usize, (i32, f32));

/// The re-decided pixels of a merged frame (ascending): `F`'s where `F` gave the pixel,
/// `G`'s where the second render gave it alone, `H`'s where a third gave it (`known`).
pub(crate) fn merged_redone(
    f_redone: &[usize],
    [g_redone, h_redone]: [&[usize]; 2],
    second: &Second,
    known: &[Pixel],
) -> Vec<usize> {
    let is_known = |p: &usize| known.iter().any(|k| k.0 == *p);
    let by_g = |p: &usize| second.complete.contains(p) && !is_known(p);
    let mut all: Vec<usize> = (f_redone.iter().copied())
        .filter(|p| !second.complete.contains(p) && !is_known(p))
        .chain(g_redone.iter().copied().filter(by_g))
        .chain(h_redone.iter().copied().filter(is_known))
        .collect();
    all.sort_unstable();
    all
}
