"""corsa.TorchDataset: a Dataset as a PyTorch map-style dataset, when torch is importable.

torch is not a dependency of Corsa: without it TorchDataset is a plain class with the same
__len__ and __getitem__, so code that only indexes it still runs.
"""

import os

try:
    from torch.utils.data import Dataset as _Base
except ImportError:  # no torch: the same protocol without the base class
    _Base = object


class TorchDataset(_Base):
    """Samples of a corsa.Dataset for a torch DataLoader.

    TorchDataset(dataset_or_folder, transform=None, sensors=None)

    A sample is transform(frame) when a transform is given, otherwise a dict of the frame's
    sensor arrays (those named in `sensors`, or all) plus 'index' and 'time', which torch's
    default collate function stacks into tensors (images of one sensor have one size). Labels
    vary in length per frame: use a transform and a collate_fn for them.
    """

    def __init__(self, dataset, transform=None, sensors=None):
        super().__init__()
        if isinstance(dataset, (str, bytes, os.PathLike)):
            from ._dataset import Dataset

            dataset = Dataset(dataset)
        self.dataset = dataset
        self.transform = transform
        self.sensors = None if sensors is None else list(sensors)

    def __len__(self):
        return len(self.dataset)

    def __getitem__(self, index):
        frame = self.dataset[index]
        if self.transform is not None:
            return self.transform(frame)
        names = frame.data if self.sensors is None else self.sensors
        sample = {name: frame.data[name] for name in names}
        sample["index"] = frame.index
        sample["time"] = frame.time
        return sample
