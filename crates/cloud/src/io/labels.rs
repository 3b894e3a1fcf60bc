//! Label and class values as files store them, made into [`Label`]s: semsim's own types are
//! taken as they are; other types are converted, and what cannot be converted is read as "no
//! entity" or "unknown class" with a note, never a reason to refuse the file. The one error:
//! a class field of semsim's own type (`U1` / `uchar`) holding a code no class has.

use super::text::Notes;
use crate::class::EntityClass;
use crate::cloud::Label;
use crate::error::{CloudError, Result};
use std::path::Path;

/// The class code stored for a value that is no class code.
const BAD_CODE: u8 = u8::MAX;

/// Converts one file's label and class values, remembering what it could not convert.
pub(crate) struct LabelConv {
    /// How the label field is named in notes (e.g. `field label (TYPE I, SIZE 4)`), and
    /// whether it has one of semsim's own types (unsigned, at most 4 bytes: no note).
    entity: Option<(String, bool)>,
    /// The same for the class field (semsim's own type: unsigned, 1 byte).
    class: Option<(String, bool)>,
    bad_entities: usize,
    first_bad_entity: Option<(usize, f64)>,
    /// Point, value and line (0: binary data) of the first value that is no class code.
    first_bad_class: Option<(usize, f64, usize)>,
}

impl LabelConv {
    pub(crate) fn new(entity: Option<(String, bool)>, class: Option<(String, bool)>) -> Self {
        LabelConv {
            entity,
            class,
            bad_entities: 0,
            first_bad_entity: None,
            first_bad_class: None,
        }
    }

    /// True where the file has a label or a class field.
    pub(crate) fn any(&self) -> bool {
        self.entity.is_some() || self.class.is_some()
    }

    /// True where the file has a class field.
    pub(crate) fn has_class(&self) -> bool {
        self.class.is_some()
    }

    /// The entity id for the label value of point `i`: 0 (no entity) where it is none.
    pub(crate) fn entity(&mut self, i: usize, v: f64) -> u32 {
        if v.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&v) {
            return v as u32;
        }
        self.bad_entities += 1;
        self.first_bad_entity.get_or_insert((i, v));
        0
    }

    /// The class code for the class value of point `i` at `line` (0 in binary data).
    pub(crate) fn class_code(&mut self, i: usize, v: f64, line: usize) -> u8 {
        let code = (v.fract() == 0.0 && (0.0..=255.0).contains(&v)).then_some(v as u8);
        match code.filter(|&c| EntityClass::from_code(c).is_some()) {
            Some(c) => c,
            None => {
                self.first_bad_class.get_or_insert((i, v, line));
                BAD_CODE
            }
        }
    }

    /// The error for a class value of semsim's own type that is no class code, if any: the
    /// readers call it as soon as they can, to stop at the first bad line.
    pub(crate) fn class_error(&self, path: &Path) -> Result<()> {
        match (&self.class, self.first_bad_class) {
            (Some((_, true)), Some((i, v, line))) => Err(CloudError::parse(
                path,
                line,
                format!("point {i}: unknown surface class code {v}"),
            )),
            _ => Ok(()),
        }
    }

    /// The labels: `labels` holds the entity ids (all 0 without a label field), `codes` the
    /// class codes (with a class field). `None` where neither field is (still) there. Notes
    /// what was converted or skipped.
    pub(crate) fn finish(
        self,
        path: &Path,
        mut labels: Vec<Label>,
        codes: Option<Vec<u8>>,
        notes: &mut Notes,
    ) -> Result<Option<Vec<Label>>> {
        self.class_error(path)?;
        if let Some((desc, own)) = &self.entity {
            if !own {
                notes.add(format_args!("{desc} read as entity ids"));
            }
            if let Some((i, v)) = self.first_bad_entity {
                let n = self.bad_entities;
                notes.add(format_args!(
                    "{n} point(s) have a label that is not an entity id (an integer 0..=4294967295), e.g. {v} at point {i}: read as no entity (0)"
                ));
            }
        }
        let mut class_kept = false;
        if let (Some((desc, own)), Some(codes)) = (&self.class, codes) {
            if let Some((i, v, _)) = self.first_bad_class {
                notes.add(format_args!(
                    "{desc} holds values that are no class code 0..=9 (e.g. {v} at point {i}): skipped, every class read as unknown"
                ));
            } else {
                if !own {
                    notes.add(format_args!("{desc} read as class codes"));
                }
                for (l, c) in labels.iter_mut().zip(codes) {
                    l.class = EntityClass::from_code(c).unwrap_or_default();
                }
                class_kept = true;
            }
        }
        Ok((self.entity.is_some() || class_kept).then_some(labels))
    }
}
