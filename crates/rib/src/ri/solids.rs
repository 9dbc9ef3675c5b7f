//! Solids, object instances and procedurals of the RI state machine (`SolidBegin`/`End`,
//! `ObjectEnd`, `ObjectInstance`, `Procedural`). Invariants: solids nest at most
//! [`MAX_SOLID_NESTING`] deep and only inside the world; an instance replays its definition
//! in an attribute block of its own, nested at most [`MAX_INSTANCE_NESTING`] deep and at most
//! [`MAX_INSTANCED_REQUESTS`] requests per world block, and must close every block it opens.

use super::frame::{
    Block, MAX_INSTANCE_NESTING, MAX_INSTANCED_REQUESTS, MAX_SOLID_NESTING, Machine, handle,
};
use crate::{Request, RibError};

impl Machine {
    pub(super) fn solid_begin(&mut self, r: &Request) -> Result<(), RibError> {
        if !self.in_world() {
            return Err(r.error("solids must be inside WorldBegin/WorldEnd"));
        }
        let op = r.string(0).unwrap_or_default().to_string();
        if !matches!(op.as_str(), "primitive" | "union" | "intersection" | "difference") {
            return Err(r.error(format!(
                "operation must be \"primitive\", \"union\", \"intersection\" or \"difference\", got \"{op}\""
            )));
        }
        if self.build.as_ref().is_some_and(|b| b.solid_depth() >= MAX_SOLID_NESTING) {
            return Err(r.error(format!("solids nested more than {MAX_SOLID_NESTING} deep")));
        }
        self.push(Block::Solid, &r.at);
        let name = self.attributes.name.clone();
        if let Some(b) = &mut self.build {
            b.solid_begin(op, name, r.at.clone());
        }
        Ok(())
    }

    pub(super) fn solid_end(&mut self, r: &Request) -> Result<(), RibError> {
        self.pop(r, Block::Solid)?;
        let b = self.build.as_mut().ok_or_else(|| r.error("no SolidBegin is open"))?;
        b.solid_end(r)
    }

    pub(super) fn object_end(&mut self, r: &Request) -> Result<(), RibError> {
        let (h, recorded, _) =
            self.recording.take().ok_or_else(|| r.error("no ObjectBegin is open"))?;
        self.objects.insert(h, recorded);
        Ok(())
    }

    pub(super) fn object_instance(&mut self, r: &Request) -> Result<(), RibError> {
        let h = handle(r, 0).ok_or_else(|| r.error("expected a handle"))?;
        let Some(requests) = self.objects.get(&h).cloned() else {
            return Err(
                r.error(format!("no object defined with handle {}", h.trim_start_matches('#')))
            );
        };
        if !self.in_world() {
            return Err(r.error("instances must be inside WorldBegin/WorldEnd"));
        }
        if self.instancing >= MAX_INSTANCE_NESTING {
            return Err(r.error(format!(
                "object instances nested more than {MAX_INSTANCE_NESTING} deep (does a \
                 definition instance itself?)"
            )));
        }
        self.instanced = self.instanced.saturating_add(requests.len());
        if self.instanced > MAX_INSTANCED_REQUESTS {
            return Err(r.error(format!(
                "object instances replay more than {MAX_INSTANCED_REQUESTS} requests in this \
                 world block"
            )));
        }
        // Replay the definition in its own attribute block.
        let depth = self.blocks.len();
        self.push(Block::Attribute, &r.at);
        self.instancing += 1;
        let replayed = requests.into_iter().try_for_each(|q| self.request(q));
        self.instancing -= 1;
        replayed?;
        if self.blocks.len() != depth + 1 {
            return Err(r.error(format!("the definition of object {h} leaves a block open")));
        }
        self.pop(r, Block::Attribute)
    }

    pub(super) fn procedural(&mut self, r: &Request) -> Result<(), RibError> {
        let name = r.string(0).unwrap_or_default();
        if name == "DelayedReadArchive" {
            let Some(file) = r.strings(1).and_then(|a| a.first()) else {
                return Err(r.error("DelayedReadArchive needs a file name"));
            };
            let path = self.archive_path(file, &r.at)?;
            return self.read_file_in_place(&path, &r.at);
        }
        if name == "RunProgram" {
            return self.run_program(r);
        }
        if name == "DynamicLoad" {
            let library = r.strings(1).and_then(|a| a.first()).map_or("", String::as_str);
            return Err(r.error(format!(
                "\"DynamicLoad\" runs the native plug-in {}, and native plug-ins are not \
                 loaded: write its geometry as RIB (DelayedReadArchive reads it)",
                crate::error::quote(library)
            )));
        }
        let w = r.warning(format!("procedural \"{name}\" is not supported: ignored"));
        self.warn_once(format!("procedural {name}"), w);
        Ok(())
    }
}
