//! Implicit conversions (assignment rules): float to a triple or matrix, between the spatial
//! types; their cost, which overload resolution minimises; types as messages show them.

use crate::error::{DResult, Diag};
use crate::ir::*;
use crate::types::{BaseType, Type};

use super::Checker;

/// The cost of converting `from` to `to` implicitly: 0 for none needed, 1 for a promotion
/// (float to a triple or matrix, one spatial type to another), `None` where none is allowed.
pub(super) fn conv_cost(from: Type, to: Type) -> Option<u32> {
    if from.array.is_some() || to.array.is_some() {
        let same_base = from.base == to.base;
        return match (from.array, to.array) {
            (Some(n), Some(m)) if same_base && (n == m || m == 0) => Some(0),
            _ => None,
        };
    }
    if from == to {
        return Some(0);
    }
    match (from.base, to.base) {
        (BaseType::Float, b) if b.is_triple() || b == BaseType::Matrix => Some(1),
        (a, b) if a.is_spatial() && b.is_spatial() => Some(1),
        _ => None,
    }
}

/// A type as messages name it.
pub(super) fn describe_type(t: Type) -> String {
    t.to_string()
}

impl Checker<'_> {
    /// `e` converted to `to` (assignment rules), or an error naming `what`.
    pub(super) fn convert(&mut self, e: Expr, to: Type, what: &str) -> DResult<Expr> {
        if e.ty == to {
            return Ok(e);
        }
        if to.array == Some(0) && e.ty.array.is_some() && e.ty.base == to.base {
            return Ok(e);
        }
        if conv_cost(e.ty, to).is_some() {
            return Ok(Expr {
                ty: to,
                detail: e.detail,
                pos: e.pos,
                kind: ExprKind::Convert(Box::new(e)),
            });
        }
        let hint = if e.ty.base.is_triple() && to.base.is_triple() {
            format!(" (write a cast: {} (...))", to.base)
        } else {
            String::new()
        };
        Err(Diag::new(e.pos, format!("{what} must be {to}, got {}{hint}", describe_type(e.ty))))
    }
}
