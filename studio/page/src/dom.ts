// Finding the page's elements by id; a missing one is a bug in index.html, said by name.
export function element<T extends HTMLElement>(id: string): T {
  const found = document.getElementById(id);
  if (!found) throw new Error(`the page has no #${id}`);
  return found as T;
}

/// Whether a key press belongs to a field (a number being typed, a menu): the page's shortcuts
/// leave it alone. A slider is not a field: its arrow keys move it, the shortcuts still work.
export function typingIn(event: KeyboardEvent): boolean {
  const target = event.target;
  return (
    (target instanceof HTMLInputElement && target.type !== 'range' && target.type !== 'checkbox') ||
    target instanceof HTMLSelectElement ||
    target instanceof HTMLTextAreaElement ||
    (target instanceof HTMLButtonElement && event.key === ' ')
  );
}

/// Sets an element's property only when it differs: the page redraws at every frame of a drag,
/// and writing even the same text or class makes the browser lay the page out again.
export function put<T extends object, K extends keyof T>(target: T, field: K, value: T[K]): void {
  if (target[field] !== value) target[field] = value;
}
