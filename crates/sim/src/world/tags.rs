//! Collider tags (the semantic entity, class and part packed into rapier's user data) and the
//! collision groups: fixed geometry, door leaves, robots and sensors.

use cloud::EntityClass;
use rapier3d::prelude::{Group, InteractionGroups, InteractionTestMode};

/// What part of an entity a collider is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Part {
    /// A fixed box (floor, ceiling, wall, lintel, furniture).
    Static,
    /// A door leaf.
    Door,
    /// A free-space sensor.
    FreeSpace,
    /// A stair step (index = step index).
    Step,
    /// A stair landing.
    Landing,
    /// A robot's chassis.
    Chassis,
    /// A robot's wheel (index = wheel index).
    Wheel,
    /// A robot's arm link (index = link index).
    ArmLink,
}

const PARTS: [Part; 8] = [
    Part::Static,
    Part::Door,
    Part::FreeSpace,
    Part::Step,
    Part::Landing,
    Part::Chassis,
    Part::Wheel,
    Part::ArmLink,
];

/// The decoded user data of a collider.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Tag {
    pub entity: u32,
    pub class: EntityClass,
    pub part: Part,
    pub index: u16,
}

impl Tag {
    pub(crate) fn pack(self) -> u128 {
        let part = PARTS.iter().position(|p| *p == self.part).unwrap_or(0) as u128;
        self.entity as u128
            | (self.class.code() as u128) << 32
            | part << 40
            | (self.index as u128) << 48
    }

    pub(crate) fn unpack(data: u128) -> Tag {
        Tag {
            entity: data as u32,
            // Every collider is tagged with a valid class; a code no class has reads as a
            // wall (as the classes' old default did).
            class: EntityClass::from_code((data >> 32) as u8).unwrap_or(EntityClass::Wall),
            part: PARTS
                .get(((data >> 40) & 0xff) as usize)
                .copied()
                .unwrap_or(Part::Static),
            index: (data >> 48) as u16,
        }
    }
}

/// Collision groups: fixed geometry, door leaves, robots, sensors.
pub(crate) const G_STATIC: Group = Group::GROUP_1;
pub(crate) const G_DOOR: Group = Group::GROUP_2;
pub(crate) const G_ROBOT: Group = Group::GROUP_3;
pub(crate) const G_SENSOR: Group = Group::GROUP_4;

pub(crate) fn groups(member: Group, filter: Group) -> InteractionGroups {
    InteractionGroups::new(member, filter, InteractionTestMode::And)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tags_round_trip() {
        let t = Tag {
            entity: 123_456,
            class: EntityClass::Stairs,
            part: Part::Landing,
            index: 6,
        };
        assert_eq!(Tag::unpack(t.pack()), t);
    }
}
