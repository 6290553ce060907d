//! Named choices (criteria, surfaces, edges, circle fits, Pareto choices, styles,
//! statuses...), each defined once.
//!
//! Every closed set of names the library offers is an enum declared with
//! [`vocabulary!`](crate::vocabulary!): one table that gives each choice its name and a
//! one-line description. The command line, the C ABI (its listing call
//! `sherd_vocabulary_entry` and its `SHERD_*` constants), Python and the add-ons take the
//! names from here, so that a name is written in one place only.

use std::ffi::CStr;

use crate::{Error, Result};

/// A closed set of named choices, declared with [`vocabulary!`](crate::vocabulary!).
pub trait Vocabulary: Copy + Eq + Send + Sync + 'static {
    /// What one choice is called in messages, e.g. `"criterion"`.
    const KIND: &'static str;
    /// What several are called, e.g. `"criteria"`.
    const PLURAL: &'static str;
    /// Every choice, in the order they are listed to users.
    const ALL: &'static [Self];

    /// The choice's name and description as NUL-terminated static strings: the table's
    /// row, kept with its NUL so that the C ABI hands it out as it is.
    fn c_strings(self) -> (&'static CStr, &'static CStr);
    /// The choice another accepted spelling stands for (`color` for `colour`).
    fn from_alias(alias: &str) -> Option<Self>;

    /// The choice's name, as users type it.
    fn name(self) -> &'static str {
        self.c_name().to_str().unwrap_or_default()
    }
    /// The name as a NUL-terminated string, for the C ABI (static: never freed).
    fn c_name(self) -> &'static CStr {
        self.c_strings().0
    }
    /// What the choice does, in one line (a tooltip or a help line).
    fn description(self) -> &'static str {
        self.c_description().to_str().unwrap_or_default()
    }
    /// The description as a NUL-terminated string, for the C ABI.
    fn c_description(self) -> &'static CStr {
        self.c_strings().1
    }

    /// The choice named `text`: ASCII case and hyphens for underscores do not matter, and
    /// aliases are accepted, as people type names both ways.
    fn find(text: &str) -> Option<Self> {
        let wanted = text.trim().to_ascii_lowercase().replace('-', "_");
        Self::ALL.iter().copied().find(|choice| choice.name() == wanted).or_else(|| Self::from_alias(&wanted))
    }

    /// [`Vocabulary::find`], or an error naming the choices.
    fn parse_name(text: &str) -> Result<Self> {
        Self::find(text).ok_or_else(|| {
            Error::InvalidArgument(format!("unknown {} {text:?}; the {} are {}", Self::KIND, Self::PLURAL, Self::names().join(", ")))
        })
    }

    /// Every name, in order.
    fn names() -> Vec<&'static str> {
        Self::ALL.iter().map(|choice| choice.name()).collect()
    }
}

/// `text` as a NUL-terminated static string; fails to compile when `text` holds a NUL.
#[doc(hidden)]
pub const fn nul_terminated(text: &'static str) -> &'static CStr {
    match CStr::from_bytes_with_nul(text.as_bytes()) {
        Ok(c_text) => c_text,
        Err(_) => panic!("a vocabulary name or description holds a NUL byte"),
    }
}

/// Declares an enum whose variants are named choices, with its [`Vocabulary`],
/// [`std::fmt::Display`] (the name) and [`std::str::FromStr`] ([`Vocabulary::parse_name`]).
///
/// ```
/// sherd::vocabulary! {
///     /// A fruit.
///     #[derive(Clone, Copy, Debug, PartialEq, Eq)]
///     pub enum Fruit: "fruit", "fruits" {
///         /// Red or green.
///         Apple = "apple" | "pomme" => "A round fruit",
///         /// Yellow.
///         Banana = "banana" => "A long fruit",
///     }
/// }
/// use sherd::vocabulary::Vocabulary;
/// assert_eq!("Pomme".parse::<Fruit>().unwrap(), Fruit::Apple);
/// assert_eq!(Fruit::Banana.to_string(), "banana");
/// assert_eq!(Fruit::names(), ["apple", "banana"]);
/// ```
#[macro_export]
macro_rules! vocabulary {
    (
        $(#[$meta:meta])*
        $vis:vis enum $enum:ident : $kind:literal, $plural:literal {
            $(
                $(#[$variant_meta:meta])*
                $variant:ident = $name:literal $(| $alias:literal)* => $description:literal
            ),+ $(,)?
        }
    ) => {
        $(#[$meta])*
        $vis enum $enum {
            $(
                $(#[$variant_meta])*
                $variant,
            )+
        }

        impl $crate::vocabulary::Vocabulary for $enum {
            const KIND: &'static str = $kind;
            const PLURAL: &'static str = $plural;
            const ALL: &'static [Self] = &[$($enum::$variant),+];

            fn c_strings(self) -> (&'static ::std::ffi::CStr, &'static ::std::ffi::CStr) {
                use $crate::vocabulary::nul_terminated;
                match self {
                    $($enum::$variant => const {
                        (nul_terminated(concat!($name, "\0")), nul_terminated(concat!($description, "\0")))
                    },)+
                }
            }

            fn from_alias(alias: &str) -> Option<Self> {
                match alias {
                    $($($alias => Some($enum::$variant),)*)+
                    _ => None,
                }
            }
        }

        impl ::std::fmt::Display for $enum {
            fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                f.pad($crate::vocabulary::Vocabulary::name(*self))
            }
        }

        impl ::std::str::FromStr for $enum {
            type Err = $crate::Error;

            fn from_str(text: &str) -> $crate::Result<Self> {
                <$enum as $crate::vocabulary::Vocabulary>::parse_name(text)
            }
        }
    };
}

/// `items` as a sentence's list: "a, b or c".
pub fn or_list<T: AsRef<str>>(items: &[T]) -> String {
    match items {
        [] => String::new(),
        [only] => only.as_ref().to_string(),
        [first @ .., last] => {
            let first: Vec<&str> = first.iter().map(AsRef::as_ref).collect();
            format!("{} or {}", first.join(", "), last.as_ref())
        }
    }
}
