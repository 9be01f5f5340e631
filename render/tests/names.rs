//! The renderer's option values read back from their names, and no two share one: the command
//! lines, the bench's rows and the report's tables depend on it.

use gbuffer_core::Named;
use gbuffer_render::gbuffers::{LayoutArgument, PackedLayout};
use gbuffer_render::on_tile::{Backend, Path};
use gbuffer_render::options::{IblForm, SunForm};

fn check_round_trip<T: Named + PartialEq + std::fmt::Debug>() {
    let names = T::names();
    for (index, value) in T::ALL.iter().enumerate() {
        assert_eq!(T::from_name(value.name()), Some(*value));
        assert!(
            !names[..index].contains(&value.name()),
            "{} named twice",
            value.name()
        );
    }
    assert_eq!(T::from_name("no-such-value"), None);
}

#[test]
fn every_name_reads_back_as_its_value_and_no_two_values_share_one() {
    check_round_trip::<PackedLayout>();
    check_round_trip::<LayoutArgument>();
    check_round_trip::<Backend>();
    check_round_trip::<Path>();
    check_round_trip::<SunForm>();
    check_round_trip::<IblForm>();
}
