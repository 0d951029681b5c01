//! Data parallelism, with or without threads: rayon with the `parallel` feature, else a
//! sequential stand-in of the same names that runs every pass on the calling thread, in order.
//!
//! Code imports `crate::par::prelude::*` (never `rayon::prelude::*`) and calls
//! [`current_num_threads`] and [`repeat_n`] from here. Every parallel pass in lanecast gives the
//! same result at any thread count (ids and depths are bit-identical on 1 thread and on many),
//! so a build without `parallel`, which is a 1-thread run, gives identical output.
//!
//! The stand-in has only what lanecast uses. Its iterators are `Seq`, a newtype around a std
//! iterator that is not itself an `Iterator`, so rayon's `reduce(identity, op)` and friends
//! never meet std's methods of the same names.

#[cfg(feature = "parallel")]
pub(crate) use rayon::{current_num_threads, iter::repeat_n};

/// rayon's prelude: its iterator traits and the `par_*` methods of slices and vectors.
#[cfg(feature = "parallel")]
pub(crate) mod prelude {
    pub(crate) use rayon::prelude::*;
}

#[cfg(not(feature = "parallel"))]
pub(crate) use seq::{current_num_threads, prelude, repeat_n};

// Built in every test run, so its tests compare it with rayon where rayon is there.
#[cfg(any(test, not(feature = "parallel")))]
#[cfg_attr(all(test, feature = "parallel"), allow(dead_code))]
mod seq {
    use std::ops::Range;

    /// The stand-in's iterator: a std iterator, run in order on the calling thread.
    pub(crate) struct Seq<I>(I);

    /// The threads a pass may use: one, the caller's.
    pub(crate) fn current_num_threads() -> usize {
        1
    }

    /// `n` clones of `x`.
    pub(crate) fn repeat_n<T: Clone>(x: T, n: usize) -> Seq<std::iter::RepeatN<T>> {
        Seq(std::iter::repeat_n(x, n))
    }

    /// The traits the `par_*` methods and the iterator methods come from.
    pub(crate) mod prelude {
        pub(crate) use super::{
            IndexedParallelIterator, IntoParallelIterator, ParallelExtend, ParallelIterator,
            ParallelSlice, ParallelSliceMut,
        };
    }

    /// rayon's iterator methods that lanecast calls, each doing what its std namesake (or, for
    /// `reduce`, a fold from `identity()`) does.
    pub(crate) trait ParallelIterator: Sized {
        /// What the iterator yields.
        type Item;
        /// The std iterator inside.
        type Iter: Iterator<Item = Self::Item>;

        /// The std iterator inside.
        fn into_seq(self) -> Self::Iter;

        fn map<R, F: FnMut(Self::Item) -> R>(self, f: F) -> Seq<std::iter::Map<Self::Iter, F>> {
            Seq(self.into_seq().map(f))
        }

        fn filter<P>(self, p: P) -> Seq<std::iter::Filter<Self::Iter, P>>
        where
            P: FnMut(&Self::Item) -> bool,
        {
            Seq(self.into_seq().filter(p))
        }

        fn flat_map_iter<U, F>(self, f: F) -> Seq<std::iter::FlatMap<Self::Iter, U, F>>
        where
            U: IntoIterator,
            F: FnMut(Self::Item) -> U,
        {
            Seq(self.into_seq().flat_map(f))
        }

        fn for_each<F: FnMut(Self::Item)>(self, f: F) {
            self.into_seq().for_each(f)
        }

        /// rayon's `try_for_each` for `Result` (its `Try` trait is not stable). Used by the
        /// parallel file read, which exists on unix only.
        #[cfg_attr(not(unix), allow(dead_code))]
        fn try_for_each<E, F>(self, f: F) -> Result<(), E>
        where
            F: FnMut(Self::Item) -> Result<(), E>,
        {
            self.into_seq().try_for_each(f)
        }

        /// rayon's `reduce`: `op` over the items, from `identity()`.
        fn reduce<ID, OP>(self, identity: ID, op: OP) -> Self::Item
        where
            ID: Fn() -> Self::Item,
            OP: Fn(Self::Item, Self::Item) -> Self::Item,
        {
            self.into_seq().fold(identity(), op)
        }

        /// The first item, in order, for which `f` gives a value.
        fn find_map_first<R, F>(self, f: F) -> Option<R>
        where
            F: FnMut(Self::Item) -> Option<R>,
        {
            self.into_seq().find_map(f)
        }

        fn collect<C: FromIterator<Self::Item>>(self) -> C {
            self.into_seq().collect()
        }

        fn sum<S: std::iter::Sum<Self::Item>>(self) -> S {
            self.into_seq().sum()
        }

        fn count(self) -> usize {
            self.into_seq().count()
        }

        fn unzip<A, B, FromA, FromB>(self) -> (FromA, FromB)
        where
            Self: ParallelIterator<Item = (A, B)>,
            FromA: Default + Extend<A>,
            FromB: Default + Extend<B>,
        {
            self.into_seq().unzip()
        }
    }

    /// rayon's methods of iterators that know each item's position.
    pub(crate) trait IndexedParallelIterator: ParallelIterator {
        fn enumerate(self) -> Seq<std::iter::Enumerate<Self::Iter>> {
            Seq(self.into_seq().enumerate())
        }

        fn zip<Z: IntoParallelIterator>(self, z: Z) -> Seq<std::iter::Zip<Self::Iter, Z::Iter>> {
            Seq(self.into_seq().zip(z.into_par_iter().0))
        }

        /// The pairs into `left` and `right`, cleared first.
        fn unzip_into_vecs<A, B>(self, left: &mut Vec<A>, right: &mut Vec<B>)
        where
            Self: ParallelIterator<Item = (A, B)>,
        {
            left.clear();
            right.clear();
            for (a, b) in self.into_seq() {
                left.push(a);
                right.push(b);
            }
        }

        /// A hint to rayon's splitting: nothing to do on one thread.
        fn with_min_len(self, _min: usize) -> Self {
            self
        }
    }

    impl<I: Iterator> ParallelIterator for Seq<I> {
        type Item = I::Item;
        type Iter = I;
        fn into_seq(self) -> I {
            self.0
        }
    }

    impl<I: Iterator> IndexedParallelIterator for Seq<I> {}

    /// `into_par_iter`, for the collections lanecast turns into parallel iterators.
    pub(crate) trait IntoParallelIterator {
        /// What the iterator yields.
        type Item;
        /// The std iterator inside.
        type Iter: Iterator<Item = Self::Item>;
        fn into_par_iter(self) -> Seq<Self::Iter>;
    }

    impl<I: Iterator> IntoParallelIterator for Seq<I> {
        type Item = I::Item;
        type Iter = I;
        fn into_par_iter(self) -> Seq<I> {
            self
        }
    }

    impl<T> IntoParallelIterator for Range<T>
    where
        Range<T>: Iterator<Item = T>,
    {
        type Item = T;
        type Iter = Range<T>;
        fn into_par_iter(self) -> Seq<Range<T>> {
            Seq(self)
        }
    }

    impl<T> IntoParallelIterator for Vec<T> {
        type Item = T;
        type Iter = std::vec::IntoIter<T>;
        fn into_par_iter(self) -> Seq<Self::Iter> {
            Seq(self.into_iter())
        }
    }

    impl<'a, T> IntoParallelIterator for &'a Vec<T> {
        type Item = &'a T;
        type Iter = std::slice::Iter<'a, T>;
        fn into_par_iter(self) -> Seq<Self::Iter> {
            Seq(self.iter())
        }
    }

    /// rayon's `par_*` methods of shared slices.
    pub(crate) trait ParallelSlice<T> {
        fn par_iter(&self) -> Seq<std::slice::Iter<'_, T>>;
        fn par_chunks(&self, size: usize) -> Seq<std::slice::Chunks<'_, T>>;
        fn par_chunks_exact(&self, size: usize) -> Seq<std::slice::ChunksExact<'_, T>>;
        fn par_windows(&self, size: usize) -> Seq<std::slice::Windows<'_, T>>;
    }

    impl<T> ParallelSlice<T> for [T] {
        fn par_iter(&self) -> Seq<std::slice::Iter<'_, T>> {
            Seq(self.iter())
        }
        fn par_chunks(&self, size: usize) -> Seq<std::slice::Chunks<'_, T>> {
            Seq(self.chunks(size))
        }
        fn par_chunks_exact(&self, size: usize) -> Seq<std::slice::ChunksExact<'_, T>> {
            Seq(self.chunks_exact(size))
        }
        fn par_windows(&self, size: usize) -> Seq<std::slice::Windows<'_, T>> {
            Seq(self.windows(size))
        }
    }

    /// rayon's `par_*` methods of mutable slices.
    pub(crate) trait ParallelSliceMut<T> {
        fn par_iter_mut(&mut self) -> Seq<std::slice::IterMut<'_, T>>;
        fn par_chunks_mut(&mut self, size: usize) -> Seq<std::slice::ChunksMut<'_, T>>;
        fn par_sort_unstable(&mut self)
        where
            T: Ord;
    }

    impl<T> ParallelSliceMut<T> for [T] {
        fn par_iter_mut(&mut self) -> Seq<std::slice::IterMut<'_, T>> {
            Seq(self.iter_mut())
        }
        fn par_chunks_mut(&mut self, size: usize) -> Seq<std::slice::ChunksMut<'_, T>> {
            Seq(self.chunks_mut(size))
        }
        fn par_sort_unstable(&mut self)
        where
            T: Ord,
        {
            self.sort_unstable()
        }
    }

    /// rayon's `par_extend` of vectors.
    pub(crate) trait ParallelExtend<T> {
        fn par_extend<I: IntoParallelIterator<Item = T>>(&mut self, items: I);
    }

    impl<T> ParallelExtend<T> for Vec<T> {
        fn par_extend<I: IntoParallelIterator<Item = T>>(&mut self, items: I) {
            self.extend(items.into_par_iter().0)
        }
    }
}

#[cfg(test)]
mod tests {
    //! The stand-in against std, and, with `parallel`, against rayon itself: every method
    //! lanecast uses gives the same result both ways.

    /// The calls lanecast makes, each result pushed as a `String`, with the prelude given
    /// (`$prelude`) in scope: the same text for the stand-in and for rayon.
    macro_rules! every_use {
        ($repeat_n:path; $($prelude:tt)+) => {{
            use $($prelude)+;
            let data: Vec<u32> = (0..1000u32).map(|i| i.wrapping_mul(2_654_435_761) % 97).collect();
            let mut out: Vec<String> = Vec::new();
            let doubled: Vec<u32> = data.par_iter().map(|&x| 2 * x).collect();
            out.push(format!("{doubled:?}"));
            let odd = data.par_iter().filter(|&&x| x % 2 == 1).count();
            out.push(format!("{odd}"));
            let sum: u64 = (0..1000u64).into_par_iter().map(|x| x * x).sum();
            out.push(format!("{sum}"));
            let (lo, hi) = data
                .par_iter()
                .map(|&x| (x, x))
                .reduce(|| (u32::MAX, 0), |a, b| (a.0.min(b.0), a.1.max(b.1)));
            out.push(format!("{lo} {hi}"));
            let sums: Vec<u32> = data.par_chunks(64).map(|c| c.iter().sum()).collect();
            out.push(format!("{sums:?}"));
            let exact: Vec<u32> = data.par_chunks_exact(64).map(|c| c[63]).collect();
            out.push(format!("{exact:?}"));
            let rising = data.par_windows(2).filter(|w| w[0] < w[1]).count();
            out.push(format!("{rising}"));
            let indexed: Vec<(usize, u32)> = data
                .par_iter()
                .enumerate()
                .zip(&data)
                .map(|((i, &a), &b)| (i, a + b))
                .collect();
            out.push(format!("{indexed:?}"));
            let flat: Vec<u32> = (0..10u32)
                .into_par_iter()
                .flat_map_iter(|q| (0..q).map(move |j| q * 100 + j))
                .collect();
            out.push(format!("{flat:?}"));
            let found = (0..100usize)
                .into_par_iter()
                .with_min_len(7)
                .find_map_first(|i| (data[i] > 90).then_some(i));
            out.push(format!("{found:?}"));
            let (evens, odds): (Vec<u32>, Vec<bool>) =
                data.clone().into_par_iter().map(|x| (x / 2, x % 2 == 1)).unzip();
            out.push(format!("{evens:?} {odds:?}"));
            let (mut halves, mut parity) = (vec![7u32], vec![true; 3]);
            data.par_iter()
                .map(|&x| (x / 2, x % 2 == 1))
                .unzip_into_vecs(&mut halves, &mut parity);
            out.push(format!("{halves:?} {parity:?}"));
            let mut grid = vec![0u32; 100];
            grid.par_chunks_mut(10).enumerate().for_each(|(row, r)| {
                r.iter_mut().enumerate().for_each(|(c, v)| *v = (row * 10 + c) as u32)
            });
            grid.par_iter_mut().for_each(|v| *v *= 3);
            let tried: Result<(), usize> = grid
                .par_chunks_mut(10)
                .enumerate()
                .try_for_each(|(k, c)| if c[0] > 150 { Err(k) } else { Ok(()) });
            out.push(format!("{grid:?} {}", tried.is_err()));
            let mut sorted = data.clone();
            sorted.par_sort_unstable();
            out.push(format!("{sorted:?}"));
            let mut ext: Vec<i32> = Vec::with_capacity(5);
            ext.par_extend($repeat_n(-1, 5));
            ext.par_extend(vec![4, 5].into_par_iter().map(|x| x * 2));
            out.push(format!("{ext:?}"));
            out
        }};
    }

    /// What std gives for each call, written out with std's own methods.
    fn expected() -> Vec<String> {
        let data: Vec<u32> = (0..1000u32)
            .map(|i| i.wrapping_mul(2_654_435_761) % 97)
            .collect();
        let grid: Vec<u32> = (0..100).map(|v| 3 * v).collect();
        let sorted = {
            let mut s = data.clone();
            s.sort();
            s
        };
        let flat: Vec<u32> = (0..10u32)
            .flat_map(|q| (0..q).map(move |j| q * 100 + j))
            .collect();
        let (evens, odds): (Vec<u32>, Vec<bool>) =
            data.iter().map(|&x| (x / 2, x % 2 == 1)).unzip();
        let tried = grid.chunks(10).any(|c| c[0] > 150);
        vec![
            format!("{:?}", data.iter().map(|&x| 2 * x).collect::<Vec<_>>()),
            format!("{}", data.iter().filter(|&&x| x % 2 == 1).count()),
            format!("{}", (0..1000u64).map(|x| x * x).sum::<u64>()),
            format!(
                "{} {}",
                data.iter().min().unwrap(),
                data.iter().max().unwrap()
            ),
            format!(
                "{:?}",
                data.chunks(64)
                    .map(|c| c.iter().sum::<u32>())
                    .collect::<Vec<_>>()
            ),
            format!(
                "{:?}",
                data.chunks_exact(64).map(|c| c[63]).collect::<Vec<_>>()
            ),
            format!("{}", data.windows(2).filter(|w| w[0] < w[1]).count()),
            format!(
                "{:?}",
                data.iter()
                    .enumerate()
                    .map(|(i, &a)| (i, 2 * a))
                    .collect::<Vec<_>>()
            ),
            format!("{flat:?}"),
            format!("{:?}", (0..100).find(|&i| data[i] > 90)),
            format!("{evens:?} {odds:?}"),
            format!("{evens:?} {odds:?}"),
            format!("{grid:?} {tried}"),
            format!("{sorted:?}"),
            "[-1, -1, -1, -1, -1, 8, 10]".to_string(),
        ]
    }

    #[test]
    fn the_stand_in_does_what_std_does() {
        assert_eq!(super::seq::current_num_threads(), 1);
        let got = every_use!(super::seq::repeat_n; super::seq::prelude::*);
        assert_eq!(got, expected());
    }

    #[cfg(feature = "parallel")]
    #[test]
    fn rayon_does_what_the_stand_in_does() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(4)
            .build()
            .unwrap();
        let got = pool.install(|| every_use!(rayon::iter::repeat_n; rayon::prelude::*));
        assert_eq!(got, expected());
    }
}
