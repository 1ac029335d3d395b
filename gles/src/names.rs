//! The name table of one kind of GL object (buffers, textures, renderbuffers, framebuffers,
//! vertex arrays): what `glGen*`, `glBind*`, `glDelete*` and `glIs*` do to names, written once.
//! Name 0 is never an object. The handlers add what differs by kind: the binding points a
//! deleted name leaves, the target a texture keeps.

use std::collections::HashMap;
use std::ops::{Deref, DerefMut};

/// The objects of one kind a context has, by name.
pub struct Names<T> {
    objects: HashMap<u32, T>,
}

impl<T> Default for Names<T> {
    fn default() -> Self {
        Names { objects: HashMap::new() }
    }
}

impl<T> Deref for Names<T> {
    type Target = HashMap<u32, T>;

    fn deref(&self) -> &HashMap<u32, T> {
        &self.objects
    }
}

impl<T> DerefMut for Names<T> {
    fn deref_mut(&mut self) -> &mut HashMap<u32, T> {
        &mut self.objects
    }
}

impl<T: Default> Names<T> {
    /// `glGen*`: every non-zero name becomes an object; names that already are keep theirs.
    pub fn generate(&mut self, names: impl IntoIterator<Item = u32>) {
        for n in names.into_iter().filter(|&n| n != 0) {
            self.objects.entry(n).or_default();
        }
    }

    /// `glBind*`: a non-zero name becomes an object on its first bind; the object, or `None`
    /// for 0.
    pub fn bind(&mut self, name: u32) -> Option<&mut T> {
        (name != 0).then(|| self.objects.entry(name).or_default())
    }
}

impl<T> Names<T> {
    /// `glDelete*`: removes every name that is an object; the names removed, in order, for
    /// the caller to clear from binding points and labels. Unknown names and 0 are ignored.
    pub fn delete(&mut self, names: impl IntoIterator<Item = u32>) -> Vec<u32> {
        names.into_iter().filter(|&n| n != 0 && self.objects.remove(&n).is_some()).collect()
    }

    /// `glIs*`: whether `name` is an object.
    pub fn is(&self, name: u32) -> bool {
        name != 0 && self.objects.contains_key(&name)
    }

    /// How many distinct non-zero names among `names` are not objects yet: what generating or
    /// binding them would add, for the quota.
    pub fn fresh(&self, names: impl IntoIterator<Item = u32>) -> u64 {
        let mut fresh: Vec<u32> = names.into_iter().filter(|&n| n != 0 && !self.objects.contains_key(&n)).collect();
        fresh.sort_unstable();
        fresh.dedup();
        fresh.len() as u64
    }
}

#[cfg(test)]
mod tests {
    use super::Names;

    #[test]
    fn gen_bind_delete_is() {
        let mut t: Names<u8> = Names::default();
        assert_eq!(t.fresh([0, 3, 3, 4]), 2, "0 is never an object; a name counts once");
        t.generate([0, 3]);
        assert!(t.is(3) && !t.is(0) && !t.is(4));
        assert_eq!(t.fresh([3, 4]), 1);
        *t.bind(3).expect("3 is a name") = 7;
        t.generate([3]);
        assert_eq!(t.get(&3), Some(&7), "generating an object again keeps it");
        assert!(t.bind(0).is_none() && !t.is(0));
        assert!(t.bind(4).is_some() && t.is(4), "binding makes an object");
        assert_eq!(t.delete([0, 9, 4, 3, 4]), vec![4, 3], "only objects are deleted, once");
        assert!(!t.is(3) && !t.is(4));
    }
}
