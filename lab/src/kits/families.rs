//! Stand-in for a list of lanecast's families that `lanecast::experimental` does not name yet:
//! the registration's families (`soa::for_each_family!`), in kind order, as one type. Once
//! lanecast names its list (`lanecast::experimental::soa::Families`), this file goes and the
//! drivers use that.

use lanecast::experimental::kernel::{Quad, Sphere, Triangle};

/// lanecast's families in kind order, as a list `(F, (G, ... ()))` ([`super::FamilyList`]).
pub type Families = (Sphere, (Triangle, (Quad, ())));
