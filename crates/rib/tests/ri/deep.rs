//! Deeply nested RIB: every nesting the state machine keeps (attribute, transform, object
//! definition, solid and instance blocks) is either kept on the heap or refused with one line
//! at the request past the limit; none exhausts the stack. Each input runs on a thread with the
//! main thread's 8 MiB stack, the stack the command line renders on.

use super::rib;

/// Runs `f` on a thread with an 8 MiB stack and returns its result.
fn on_a_main_sized_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    let worker = std::thread::Builder::new().stack_size(8 << 20).spawn(f);
    match worker.map(|h| h.join()) {
        Ok(Ok(value)) => value,
        _ => panic!("the deep input failed on an 8 MiB stack"),
    }
}

/// A frame whose world holds `body`.
fn world(body: String) -> String {
    format!(
        "Format 32 24 1\nProjection \"perspective\" \"fov\" [40]\nWorldBegin\nTranslate 0 0 5\n{body}WorldEnd\n"
    )
}

/// Loads `text` on an 8 MiB stack: the number of frames, or the one-line error.
fn load(text: String) -> Result<usize, String> {
    on_a_main_sized_stack(move || rib(&text).map(|l| l.frames.len()).map_err(|e| e.to_string()))
}

const SPHERE: &str = "Sphere 1 -1 1 360\n";

#[test]
fn attribute_blocks_200000_deep() {
    let n = 200_000;
    let body = format!("{}{SPHERE}{}", "AttributeBegin\n".repeat(n), "AttributeEnd\n".repeat(n));
    assert_eq!(load(world(body)), Ok(1));
}

#[test]
fn transform_blocks_200000_deep() {
    let n = 200_000;
    let body = format!("{}{SPHERE}{}", "TransformBegin\n".repeat(n), "TransformEnd\n".repeat(n));
    assert_eq!(load(world(body)), Ok(1));
}

#[test]
fn object_definitions_200000_deep() {
    let n = 200_000;
    let body = format!("{}{SPHERE}{}", "ObjectBegin 1\n".repeat(n), "ObjectEnd\n".repeat(n));
    assert_eq!(load(world(body)), Ok(1));
}

/// 64 solids open at once make a CSG tree within the model's depth; the 65th `SolidBegin` is
/// refused where it stands, however many follow.
#[test]
fn solids_nest_at_most_64_deep() {
    let nested = |n: usize| {
        let mut body = String::new();
        for i in 0..n {
            body.push_str(&format!("SolidBegin \"difference\"\nSolidBegin \"primitive\"\nSphere {} -{0} {0} 360\nSolidEnd\n", 2.0 + i as f32));
        }
        body.push_str("SolidBegin \"primitive\"\nSphere 0.5 -0.5 0.5 360\nSolidEnd\n");
        body.push_str(&"SolidEnd\n".repeat(n));
        world(body)
    };
    // 63 differences and the innermost primitive: 64 open.
    assert_eq!(load(nested(63)), Ok(1));
    let e = load(nested(100_000)).err().unwrap_or_default();
    // Level i's blocks start on line 5 + 4i; the primitive of level 63 is the 65th open.
    assert_eq!(e, "test.rib:258:1: SolidBegin: solids nested more than 64 deep");
}

/// A chain of definitions each instancing the one before replays 64 deep at most.
#[test]
fn instances_nest_at_most_64_deep() {
    let chain = |n: usize| {
        let mut body = format!("ObjectBegin \"o0\"\n{SPHERE}ObjectEnd\n");
        for i in 1..n {
            body.push_str(&format!(
                "ObjectBegin \"o{i}\"\nObjectInstance \"o{}\"\nObjectEnd\n",
                i - 1
            ));
        }
        body.push_str(&format!("ObjectInstance \"o{}\"\n", n - 1));
        world(body)
    };
    assert_eq!(load(chain(64)), Ok(1));
    let e = load(chain(100_000)).err().unwrap_or_default();
    assert!(e.ends_with("ObjectInstance: object instances nested more than 64 deep (does a definition instance itself?)"), "{e}");
}

/// An object redefined to instance its own handle would replay forever.
#[test]
fn an_object_that_instances_itself() {
    let body = format!(
        "ObjectBegin \"a\"\n{SPHERE}ObjectEnd\nObjectBegin \"a\"\nObjectInstance \"a\"\nObjectEnd\nObjectInstance \"a\"\n"
    );
    let e = load(world(body)).err().unwrap_or_default();
    assert!(
        e.starts_with("test.rib:9:1: ObjectInstance: object instances nested more than 64"),
        "{e}"
    );
}

/// Definitions that each instance the one before twice double at every level: 30 levels
/// would replay 2^30 requests, and are refused after 2^20.
#[test]
fn instances_that_double_at_every_level() {
    let mut body = format!("ObjectBegin \"o0\"\n{SPHERE}ObjectEnd\n");
    for i in 1..30 {
        body.push_str(&format!(
            "ObjectBegin \"o{i}\"\nObjectInstance \"o{0}\"\nObjectInstance \"o{0}\"\nObjectEnd\n",
            i - 1
        ));
    }
    body.push_str("ObjectInstance \"o29\"\n");
    let e = load(world(body)).err().unwrap_or_default();
    assert!(
        e.ends_with(
            "ObjectInstance: object instances replay more than 1048576 requests in this world block"
        ),
        "{e}"
    );
}
