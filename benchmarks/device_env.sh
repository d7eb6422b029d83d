# Sourced at the start of a command on a GPU host that has an NVIDIA driver but no Vulkan
# loader: unpacks the carried Debian libvulkan1 (.gl/) and points the loader at the driver's ICD.
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
if [ -z "${VK_DRIVER_FILES:-}" ]; then
  icd=$(find /usr/local/nvidia /usr/share/vulkan /etc/vulkan /usr/lib /usr/lib64 -name 'nvidia_icd*.json' 2>/dev/null | head -n 1)
  if [ -n "$icd" ]; then
    export VK_DRIVER_FILES=$icd
  else
    # No ICD manifest shipped: write one for the driver's library, wherever it is.
    lib=$(find / -xdev -name 'libGLX_nvidia.so.0' 2>/dev/null | head -n 1)
    if [ -n "$lib" ]; then
      printf '{"file_format_version":"1.0.1","ICD":{"library_path":"%s","api_version":"1.3.0"}}\n' "$lib" >/tmp/nvidia_icd.json
      export VK_DRIVER_FILES=/tmp/nvidia_icd.json
    fi
  fi
fi
echo "Vulkan ICD: ${VK_DRIVER_FILES:-none found}"
