//! A fixed-capacity vector on the stack, so hot paths never allocate.

/// A vector of at most `N` elements stored inline. Pushing beyond capacity is reported
/// (`try_push` returns `false`) instead of panicking or allocating.
#[derive(Clone, Copy)]
pub struct FixedVec<T: Copy + Default, const N: usize> {
    items: [T; N],
    len: usize,
}

impl<T: Copy + Default, const N: usize> Default for FixedVec<T, N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T: Copy + Default, const N: usize> FixedVec<T, N> {
    /// An empty vector.
    pub fn new() -> Self {
        Self {
            items: [T::default(); N],
            len: 0,
        }
    }
    /// Appends `item`; returns `false` (and drops it) when the vector is full.
    pub fn try_push(&mut self, item: T) -> bool {
        if self.len < N {
            self.items[self.len] = item;
            self.len += 1;
            true
        } else {
            false
        }
    }
    /// Removes and returns the last element.
    pub fn pop(&mut self) -> Option<T> {
        if self.len == 0 {
            None
        } else {
            self.len -= 1;
            Some(self.items[self.len])
        }
    }
    /// Number of stored elements.
    pub fn len(&self) -> usize {
        self.len
    }
    /// True when no element is stored.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
    /// Removes all elements.
    pub fn clear(&mut self) {
        self.len = 0;
    }
    /// Keeps the first `len` elements.
    pub fn truncate(&mut self, len: usize) {
        self.len = self.len.min(len);
    }
    /// The stored elements.
    pub fn as_slice(&self) -> &[T] {
        &self.items[..self.len]
    }
    /// The stored elements, mutable.
    pub fn as_mut_slice(&mut self) -> &mut [T] {
        &mut self.items[..self.len]
    }
}

impl<T: Copy + Default, const N: usize> std::ops::Deref for FixedVec<T, N> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        self.as_slice()
    }
}

impl<T: Copy + Default, const N: usize> std::ops::DerefMut for FixedVec<T, N> {
    fn deref_mut(&mut self) -> &mut [T] {
        self.as_mut_slice()
    }
}

impl<T: Copy + Default + std::fmt::Debug, const N: usize> std::fmt::Debug for FixedVec<T, N> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.as_slice()).finish()
    }
}
