//! Re-writing parsed MJCF elements as text, with their attributes edited on the way.

use roxmltree::Node;

/// The attributes of an element, in document order, as owned pairs.
pub(super) type Attributes = Vec<(String, String)>;

/// Set `name` to `value`, replacing it where it is.
pub(super) fn set(attributes: &mut Attributes, name: &str, value: String) {
    match attributes.iter_mut().find(|(n, _)| n == name) {
        Some((_, v)) => *v = value,
        None => attributes.push((name.to_string(), value)),
    }
}

/// The value of `name`, if present.
pub(super) fn get<'a>(attributes: &'a Attributes, name: &str) -> Option<&'a str> {
    attributes
        .iter()
        .find(|(n, _)| n == name)
        .map(|(_, v)| v.as_str())
}

/// `node` and its element children as MJCF text indented by `depth` levels; `edit` sees every
/// element (the node itself included) with its attributes before it is written. Comments and
/// text between elements are left out.
pub(super) fn copy(
    node: Node<'_, '_>,
    depth: usize,
    edit: &mut dyn FnMut(Node<'_, '_>, &mut Attributes),
) -> String {
    let mut out = String::new();
    write(node, depth, edit, &mut out);
    out
}

fn write(
    node: Node<'_, '_>,
    depth: usize,
    edit: &mut dyn FnMut(Node<'_, '_>, &mut Attributes),
    out: &mut String,
) {
    let tag = node.tag_name().name();
    let mut attributes: Attributes = node
        .attributes()
        .map(|a| (a.name().to_string(), a.value().to_string()))
        .collect();
    edit(node, &mut attributes);
    let pad = "  ".repeat(depth);
    out.push_str(&format!("{pad}<{tag}"));
    for (name, value) in &attributes {
        out.push_str(&format!(" {name}=\"{}\"", escape(value)));
    }
    let children: Vec<_> = node.children().filter(Node::is_element).collect();
    if children.is_empty() {
        out.push_str("/>\n");
        return;
    }
    out.push_str(">\n");
    for child in children {
        write(child, depth + 1, edit, out);
    }
    out.push_str(&format!("{pad}</{tag}>\n"));
}

/// `text` safe inside a double-quoted XML attribute.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
