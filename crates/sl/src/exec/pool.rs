//! Reused float buffers. Every varying value of the machine is a `Vec<f32>` of a lane per
//! point, and almost every node makes one; on a grid of a few hundred points the allocator's
//! work for these (kilobytes each, too large for its fast per-thread caches) was a tenth of a
//! run. Buffers the machine knows are dead are given back here ([`recycle`]) and
//! [`Num::zeros`](super::Num::zeros) and [`dup`] take from here first.
//!
//! One pool per thread (grids are shaded on the renderer's worker threads), bounded in count
//! and in the size of a buffer it keeps, so it never holds more than a few megabytes.

use std::cell::RefCell;
use std::rc::Rc;

use super::LightSample;
use super::value::{Num, Value};

/// Buffers kept per thread.
const MAX_BUFFERS: usize = 64;
/// The smallest buffer worth keeping (smaller ones are cheap for the allocator).
const MIN_FLOATS: usize = 16;
/// The largest buffer kept (64 KiB: a 64 x 64 grid of triples): larger grids allocate as before.
const MAX_FLOATS: usize = 1 << 14;

thread_local! {
    static POOL: RefCell<Vec<Vec<f32>>> = const { RefCell::new(Vec::new()) };
}

/// A buffer of `len` zeros, reused when the pool has one large enough.
pub(crate) fn zeros(len: usize) -> Vec<f32> {
    let mut v = take(len);
    v.resize(len, 0.0);
    v
}

/// An empty buffer with room for `len` floats, reused when the pool has one.
pub(crate) fn take(len: usize) -> Vec<f32> {
    if (MIN_FLOATS..=MAX_FLOATS).contains(&len) {
        let found = POOL
            .try_with(|p| {
                let mut p = p.try_borrow_mut().ok()?;
                let j = p.iter().rposition(|b| b.capacity() >= len)?;
                Some(p.swap_remove(j))
            })
            .ok()
            .flatten();
        if let Some(mut v) = found {
            v.clear();
            return v;
        }
    }
    Vec::with_capacity(len)
}

/// A copy of `x` in a pooled buffer.
pub(crate) fn dup(x: &Num) -> Num {
    let mut data = take(x.data.len());
    data.extend_from_slice(&x.data);
    Num { w: x.w, varying: x.varying, data }
}

/// Gives a dead buffer back.
pub(crate) fn give(v: Vec<f32>) {
    if !(MIN_FLOATS..=MAX_FLOATS).contains(&v.capacity()) {
        return;
    }
    let _ = POOL.try_with(|p| {
        if let Ok(mut p) = p.try_borrow_mut()
            && p.len() < MAX_BUFFERS
        {
            p.push(v);
        }
    });
}

/// The lights a grid asked for last: the position, the category, and the lights.
pub(crate) type LightCache = (Num, String, Rc<[LightSample]>);

/// Gives the buffers of the cached lights back (those the cache alone holds).
pub(crate) fn recycle_lights(cache: Option<LightCache>) {
    let Some((p, _, mut samples)) = cache else { return };
    give(p.data);
    if let Some(samples) = Rc::get_mut(&mut samples) {
        for s in samples {
            for x in [&mut s.l, &mut s.cl, &mut s.ol] {
                give(std::mem::take(&mut x.data));
            }
        }
    }
}

/// Gives a dead value's buffers back.
pub(crate) fn recycle(v: Value) {
    match v {
        Value::Num(x) => give(x.data),
        Value::Array(xs) => xs.into_iter().for_each(recycle),
        Value::Str(_) => {}
    }
}

/// What gives its buffers back to the pool when dropped inside a [`Pooled`].
pub(crate) trait Recycle {
    /// Gives the buffers back, leaving `self` empty.
    fn recycle(&mut self);
}

impl Recycle for Vec<Value> {
    fn recycle(&mut self) {
        self.drain(..).for_each(recycle);
    }
}

impl Recycle for Vec<Option<Value>> {
    fn recycle(&mut self) {
        self.iter_mut().filter_map(Option::take).for_each(recycle);
    }
}

impl Recycle for Option<LightCache> {
    fn recycle(&mut self) {
        recycle_lights(self.take());
    }
}

/// A grid's variables or globals, whose buffers go back to this thread's pool (for the
/// next grid) when the grid is dropped. (A `Drop` on the grid itself would make its borrows
/// of the lights and textures outlive it.)
pub(crate) struct Pooled<T: Recycle>(pub(crate) T);

impl<T: Recycle> Drop for Pooled<T> {
    fn drop(&mut self) {
        self.0.recycle();
    }
}

impl<T: Recycle> std::ops::Deref for Pooled<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.0
    }
}

impl<T: Recycle> std::ops::DerefMut for Pooled<T> {
    fn deref_mut(&mut self) -> &mut T {
        &mut self.0
    }
}
