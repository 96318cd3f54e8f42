//! Flags that name a method, mode, benchmark or disturbance level, read through the catalogue
//! (`lfd::catalogue`): `--help` lists each id with its description, and an unknown name is
//! refused with the ids it could have been.

use std::ffi::OsStr;
use std::marker::PhantomData;

use clap::builder::{PossibleValue, TypedValueParser};
use clap::error::ErrorKind;
use logic_lfd::lfd::Listed;

/// The value parser of a flag that takes one id of `T` (or, with [`or_none`], also `none`).
#[derive(Clone)]
pub struct Ids<T> {
    /// The description of `none`, when the flag takes it.
    none: Option<&'static str>,
    kind: PhantomData<T>,
}

/// A flag that takes one id of `T`.
pub fn one<T>() -> Ids<T> {
    Ids {
        none: None,
        kind: PhantomData,
    }
}

/// A flag that takes one id of `T` or `none` (described by `none`), parsed as an `Option`.
pub fn or_none<T>(none: &'static str) -> OrNone<T> {
    OrNone(Ids {
        none: Some(none),
        kind: PhantomData,
    })
}

impl<T: Listed> Ids<T> {
    fn read(&self, cmd: &clap::Command, value: &OsStr) -> Result<Option<T>, clap::Error> {
        let s = value.to_string_lossy();
        if self.none.is_some() && s == "none" {
            return Ok(None);
        }
        T::from_id(&s).map(Some).map_err(|e| {
            let e = match self.none {
                Some(_) => format!("{e} or none"),
                None => e.to_string(),
            };
            clap::Error::raw(ErrorKind::InvalidValue, format!("{e}\n")).with_cmd(cmd)
        })
    }

    fn values(&self) -> Box<dyn Iterator<Item = PossibleValue> + '_> {
        let ids = T::all()
            .iter()
            .map(|x| PossibleValue::new(x.id()).help(x.description()));
        Box::new(ids.chain(self.none.map(|d| PossibleValue::new("none").help(d))))
    }
}

impl<T: Listed + Send + Sync> TypedValueParser for Ids<T> {
    type Value = T;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        _arg: Option<&clap::Arg>,
        value: &OsStr,
    ) -> Result<T, clap::Error> {
        self.read(cmd, value)?
            .ok_or_else(|| clap::Error::new(ErrorKind::InvalidValue).with_cmd(cmd))
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(self.values())
    }
}

/// The value parser of [`or_none`].
#[derive(Clone)]
pub struct OrNone<T>(Ids<T>);

impl<T: Listed + Send + Sync> TypedValueParser for OrNone<T> {
    type Value = Option<T>;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        _arg: Option<&clap::Arg>,
        value: &OsStr,
    ) -> Result<Option<T>, clap::Error> {
        self.0.read(cmd, value)
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(self.0.values())
    }
}
