//! Command-line values that name a choice of one of the library's vocabularies
//! (`--refine circles`, `--placement true-distance`): the names come from the library,
//! hyphenated as option values are, with the library's own spelling accepted too.

use std::ffi::OsStr;

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};

use sherd::vocabulary::Vocabulary;

/// The command-line spelling of a library name: words joined by hyphens.
pub fn cli_name<T: Vocabulary>(choice: T) -> String {
    choice.name().replace('_', "-")
}

/// The values an option accepts, each with the value it gives; parsed as clap parses a
/// `ValueEnum`, so that errors and help list the possible values the same way.
#[derive(Clone)]
pub struct Choices<T> {
    values: Vec<(T, PossibleValue)>,
}

impl<T: Clone + Send + Sync + 'static> Choices<T> {
    /// Every choice of the vocabulary `V`, in the library's order; `help` gives a value
    /// its help line in `--help` (most need none: the name says it).
    pub fn of<V: Vocabulary>(help: fn(V) -> Option<&'static str>, value: impl Fn(V) -> T) -> Choices<T> {
        let values = V::ALL
            .iter()
            .map(|&choice| {
                let mut possible = PossibleValue::new(cli_name(choice)).help(help(choice));
                if choice.name() != cli_name(choice) {
                    possible = possible.alias(choice.name());
                }
                (value(choice), possible)
            })
            .collect();
        Choices { values }
    }

    /// These choices and one more, `value` under `name`, listed last.
    pub fn and(mut self, value: T, name: &'static str, help: &'static str) -> Choices<T> {
        self.values.push((value, PossibleValue::new(name).help(help)));
        self
    }
}

impl<T: Clone + Send + Sync + 'static> TypedValueParser for Choices<T> {
    type Value = T;

    fn parse_ref(&self, command: &clap::Command, argument: Option<&clap::Arg>, text: &OsStr) -> Result<T, clap::Error> {
        let possible: Vec<PossibleValue> = self.values.iter().map(|(_, possible)| possible.clone()).collect();
        let given = PossibleValuesParser::new(possible).parse_ref(command, argument, text)?;
        let (value, _) = self
            .values
            .iter()
            .find(|(_, possible)| possible.matches(&given, false))
            .expect("PossibleValuesParser accepts only the possible values");
        Ok(value.clone())
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(self.values.iter().map(|(_, possible)| possible.clone())))
    }
}
