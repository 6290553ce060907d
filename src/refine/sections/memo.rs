//! Values derived from a prepared surface's points that the criteria ask for again and
//! again: one refinement and the edge tests around it build the same vertical sections
//! and the same candidate extremes several times over (on a 200k-face sherd 59 times,
//! 22 of them distinct, a twelfth of the whole pipeline's instructions).

use std::any::{Any, TypeId};
use std::sync::{Arc, Mutex};

type Entry = (TypeId, u64, Arc<dyn Any + Send + Sync>);

/// A value per type and key, made on first demand and shared afterwards. The asker
/// chooses the key; a value must depend on the surface's points and the key alone.
#[derive(Default)]
pub struct Memo {
    entries: Mutex<Vec<Entry>>,
}

impl Memo {
    /// The value of type `T` under `key`, made by `make` when there is none yet. `make`
    /// runs without the lock held: two threads asking at once may both make it, and the
    /// first stored is kept (they are equal).
    pub fn get_or_make<T: Any + Send + Sync>(&self, key: u64, make: impl FnOnce() -> T) -> Arc<T> {
        if let Some(found) = self.find::<T>(key) {
            return found;
        }
        let made: Arc<dyn Any + Send + Sync> = Arc::new(make());
        let mut entries = self.entries.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        let kept = match entries.iter().find(|(kind, k, _)| *kind == TypeId::of::<T>() && *k == key) {
            Some((_, _, value)) => Arc::clone(value),
            None => {
                entries.push((TypeId::of::<T>(), key, Arc::clone(&made)));
                made
            }
        };
        kept.downcast::<T>().expect("stored under its own type")
    }

    fn find<T: Any + Send + Sync>(&self, key: u64) -> Option<Arc<T>> {
        let entries = self.entries.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        let (_, _, value) = entries.iter().find(|(kind, k, _)| *kind == TypeId::of::<T>() && *k == key)?;
        Some(Arc::clone(value).downcast::<T>().expect("stored under its own type"))
    }
}

/// A copy shares the values made so far: they depend on the points, which a copy keeps.
impl Clone for Memo {
    fn clone(&self) -> Self {
        let entries = self.entries.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        Memo { entries: Mutex::new(entries.clone()) }
    }
}

impl std::fmt::Debug for Memo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let count = self.entries.lock().map_or(0, |entries| entries.len());
        write!(f, "Memo({count} values)")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_is_made_once_per_type_and_key() {
        let memo = Memo::default();
        let mut made = 0;
        let first = memo.get_or_make(7, || {
            made += 1;
            vec![1, 2, 3]
        });
        let again = memo.get_or_make(7, || {
            made += 1;
            vec![9]
        });
        assert_eq!(made, 1);
        assert!(Arc::ptr_eq(&first, &again));
        assert_eq!(*memo.get_or_make(8, || vec![4]), vec![4]);
        assert_eq!(*memo.get_or_make(7, || 5u8), 5, "another type under the same key");
        let copy = memo.clone();
        assert!(Arc::ptr_eq(&copy.get_or_make(7, Vec::<i32>::new), &first));
    }
}
