//! The builders of the built-in systems are the library's own functions, not copies in the crate
//! that names `ddirac::systems::BUILT_IN`.
//!
//! Each builder instantiates the whole engine for its system type (`Erased<S, N>` and its stepper). As a
//! `const`, the table was copied into every crate naming it, and its builders with it: the command line
//! compiled six copies of the engine of its own (recompiling it took 54 s with them, 30 s without).
//! Then the table and the builders named here are others than those `find` (compiled in the library)
//! returns.

use ddirac::systems::{find, BUILT_IN};

#[test]
fn the_table_named_here_is_the_library_table() {
    for entry in BUILT_IN {
        let from_library = find(entry.name).expect("every listed system is found by its name");
        assert!(std::ptr::eq(entry, from_library), "`{}`: BUILT_IN names a copy of the library's table", entry.name);
        assert_eq!(
            entry.build as usize, from_library.build as usize,
            "`{}`: the builder named here is a copy compiled in this crate, not the library's",
            entry.name
        );
        assert_eq!(entry.defaults as usize, from_library.defaults as usize, "`{}`: defaults", entry.name);
    }
}
